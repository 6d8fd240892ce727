//! `vpx-efis config`: the config file's path and every effective setting with where it
//! came from (flag, environment, config file and line, or default), so a person can
//! see why the page opened the port it did.

use std::io::Write;

use anyhow::Context;
use clap::Args;

use crate::cmd::common::{PortArgs, XfspArgs};
use crate::settings::values::Theme as Requested;
use crate::settings::{BAUD_ENV, CONFIG_ENV, KEYS, Origin, PORT_ENV};

#[derive(Debug, Args)]
pub struct ConfigArgs {
    /// The same options the commands take, to see how they combine with the file.
    #[command(flatten)]
    pub port: PortArgs,
    #[command(flatten)]
    pub xfsp: XfspArgs,
    /// Colours, as the page's --theme.
    #[arg(long, value_enum, default_value_t = Requested::Auto)]
    pub theme: Requested,
    /// The first key auto-repeat, as the page's --repeat-delay.
    #[arg(long, value_name = "MS")]
    pub repeat_delay: Option<u64>,
}

/// One effective setting for `vpx-efis config`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Effective {
    pub key: &'static str,
    pub value: String,
    pub origin: Origin,
}

pub fn run(report: &[Effective]) -> anyhow::Result<()> {
    let mut out = std::io::stdout().lock();
    write!(out, "{}", render(report)).context("cannot write to standard output")?;
    out.flush().context("cannot write to standard output")
}

/// The text `config` prints: one aligned line per setting, then where to change them.
pub fn render(report: &[Effective]) -> String {
    let key_w = report.iter().map(|e| e.key.len()).max().unwrap_or(0);
    let val_w = report
        .iter()
        .skip(1)
        .map(|e| e.value.chars().count())
        .max()
        .unwrap_or(0);
    let mut s = String::new();
    for (i, e) in report.iter().enumerate() {
        if i == 0 && e.key == "config file" {
            let whose = match e.origin {
                Origin::Env(name) => format!("named by {name}"),
                _ => "the OS's configuration folder".into(),
            };
            s.push_str(&format!("{:key_w$}  {}  [{whose}]\n", e.key, e.value));
            continue;
        }
        s.push_str(&format!(
            "{:key_w$}  {:val_w$}  {}\n",
            e.key, e.value, e.origin
        ));
    }
    s.push_str(&format!(
        "\nFlags win over the environment ({PORT_ENV}, {BAUD_ENV}), which wins over the file.\n\
         The file is TOML; its keys: {}. {CONFIG_ENV} names another file.\n",
        KEYS.join(", ")
    ));
    s
}
