//! The guide's reference pages (`docs/src/reference/*.md`), generated from the code that
//! defines what they describe, never typed: clap's own definitions give the command
//! line, [`crate::control::keymap::HELP`] the keys, the settings table the config keys
//! and environment variables, [`crate::remote::routes`] the HTTP API,
//! [`crate::program::exit::MEANINGS`] the exit codes, the codec crate's Table 43 with
//! [`crate::check::advice`] the fault codes, and the virtual unit's console help its
//! commands.
//!
//! `vpx-efis reference [DIR]`, a hidden subcommand (`cargo run -- reference`), writes
//! them; `tests/reference_pages.rs` regenerates them and fails when a committed page
//! differs. It lives here, on top, because it reads every layer.

use std::fmt::Write as _;
use std::path::Path;

use anyhow::Context;
use clap::{Arg, ArgAction, CommandFactory};

use crate::check::advice;
use crate::cli::Cli;
use crate::control::keymap;
use crate::program::exit;
use crate::protocol::fault::{FAULT_TABLE, FaultCode};
use crate::remote::routes;
use crate::settings;
use crate::sim::console;

/// Where the pages go, from the repository's root.
pub const DIR: &str = "docs/src/reference";

/// The one command that regenerates every page, for the test's failure message.
pub const REGENERATE: &str = "cargo run -- reference";

/// Every page: its file name under [`DIR`] and its text.
pub fn pages() -> Vec<(&'static str, String)> {
    vec![
        ("command-line.md", command_line()),
        ("keys.md", keys()),
        ("configuration.md", configuration()),
        ("http-api.md", http_api()),
        ("exit-codes.md", exit_codes()),
        ("fault-codes.md", fault_codes()),
        ("sim-console.md", sim_console()),
    ]
}

/// Writes every page into `dir` (made if missing); says which changed.
pub fn run(dir: &Path) -> anyhow::Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("cannot make {}", dir.display()))?;
    for (name, text) in pages() {
        let path = dir.join(name);
        let old = std::fs::read_to_string(&path).unwrap_or_default();
        if old != text {
            std::fs::write(&path, &text)
                .with_context(|| format!("cannot write {}", path.display()))?;
            println!("wrote {}", path.display());
        } else {
            println!("unchanged {}", path.display());
        }
    }
    Ok(())
}

fn header(title: &str, source: &str) -> String {
    format!(
        "<!-- Generated from {source} by `{REGENERATE}`: do not edit by hand. -->\n\n# {title}\n\n"
    )
}

/// Text for Markdown prose: a `<` outside backticks would start an HTML tag, and a
/// `|` would end a table's cell.
fn prose(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut in_code = false;
    for c in text.chars() {
        match c {
            '`' => {
                in_code = !in_code;
                out.push(c);
            }
            '<' if !in_code => out.push_str("&lt;"),
            '>' if !in_code => out.push_str("&gt;"),
            '*' if !in_code => out.push_str("\\*"),
            _ => out.push(c),
        }
    }
    out
}

fn cell(text: &str) -> String {
    prose(text).replace('|', "\\|").replace('\n', " ")
}

// ---- the command line ----

fn command_line() -> String {
    let mut cmd = Cli::command();
    cmd.build();
    let mut out = header(
        "The command line",
        "clap's definitions (`src/cli/args.rs` and each `src/cmd/` file)",
    );
    out.push_str(
        "Every subcommand and option, as `vpx-efis --help` and `vpx-efis SUBCOMMAND --help` \
         give them. An option's environment variable and the config file's key (see \
         [Configuration](configuration.md)) give it a value when the command line does \
         not.\n\n",
    );
    out.push_str("Subcommands:\n\n");
    for sub in visible_subcommands(&cmd) {
        let name = sub.get_name();
        let about = sub.get_about().map(|a| a.to_string()).unwrap_or_default();
        let first = about.lines().next().unwrap_or("");
        let _ = writeln!(out, "- [`{name}`](#vpx-efis-{name}): {}", prose(first));
    }
    out.push('\n');
    command_section(&mut out, &cmd, "vpx-efis");
    for sub in visible_subcommands(&cmd) {
        command_section(&mut out, sub, &format!("vpx-efis {}", sub.get_name()));
    }
    out
}

fn visible_subcommands(cmd: &clap::Command) -> Vec<&clap::Command> {
    cmd.get_subcommands()
        .filter(|s| !s.is_hide_set() && s.get_name() != "help")
        .collect()
}

fn command_section(out: &mut String, cmd: &clap::Command, title: &str) {
    let _ = writeln!(out, "## {title}\n");
    if let Some(about) = cmd.get_long_about().or(cmd.get_about()) {
        let _ = writeln!(out, "{}\n", prose(about.to_string().trim()));
    }
    let usage = cmd.clone().render_usage().to_string();
    let usage = usage.trim().trim_start_matches("Usage:").trim();
    // A subcommand's own usage names only itself; say the program's name too.
    let usage = if title != "vpx-efis" && !usage.starts_with("vpx-efis") {
        format!("vpx-efis {usage}")
    } else {
        usage.to_string()
    };
    let _ = writeln!(out, "```text\n{usage}\n```\n");
    let args: Vec<&Arg> = cmd
        .get_arguments()
        .filter(|a| !a.is_hide_set() && !matches!(a.get_id().as_str(), "help" | "version"))
        .collect();
    for arg in args {
        argument(out, arg);
    }
    if let Some(after) = cmd.get_after_long_help().or(cmd.get_after_help()) {
        let _ = writeln!(out, "```text\n{}\n```\n", after.to_string().trim_end());
    }
}

fn argument(out: &mut String, arg: &Arg) {
    let value = arg
        .get_value_names()
        .map(|names| {
            names
                .iter()
                .map(|n| format!("<{n}>"))
                .collect::<Vec<_>>()
                .join(" ")
        })
        .unwrap_or_else(|| format!("<{}>", arg.get_id().as_str().to_ascii_uppercase()));
    let takes = arg.get_action().takes_values();
    let optional_value = arg.get_num_args().is_some_and(|n| n.min_values() == 0);
    let repeated = matches!(arg.get_action(), ArgAction::Append);
    let mut name = match (arg.get_short(), arg.get_long()) {
        (Some(s), Some(l)) => format!("-{s}, --{l}"),
        (None, Some(l)) => format!("--{l}"),
        (Some(s), None) => format!("-{s}"),
        (None, None) => value.clone(),
    };
    if arg.get_long().is_some() || arg.get_short().is_some() {
        if takes && optional_value {
            name.push_str(&format!(" [{value}]"));
        } else if takes {
            name.push_str(&format!(" {value}"));
        }
    }
    if repeated {
        name.push_str(" …");
    }
    let help = arg
        .get_long_help()
        .or(arg.get_help())
        .map(|h| h.to_string())
        .unwrap_or_default();
    let mut paragraphs = help.trim().split("\n\n");
    let first = paragraphs.next().unwrap_or("");
    let _ = writeln!(out, "- `{name}`: {}", prose(&first.replace('\n', " ")));
    for p in paragraphs {
        let _ = writeln!(out, "\n  {}", prose(&p.replace('\n', " ")));
    }
    let mut facts = Vec::new();
    let possible: Vec<_> = arg
        .get_possible_values()
        .into_iter()
        .filter(|p| !p.is_hide_set())
        .collect();
    if takes && !possible.is_empty() {
        let words: Vec<String> = possible
            .iter()
            .map(|p| match p.get_help() {
                Some(h) => format!("`{}` ({})", p.get_name(), prose(&h.to_string())),
                None => format!("`{}`", p.get_name()),
            })
            .collect();
        facts.push(format!("One of {}.", words.join(", ")));
    }
    let defaults: Vec<String> = arg
        .get_default_values()
        .iter()
        .map(|d| d.to_string_lossy().into_owned())
        .collect();
    if takes && !defaults.is_empty() && !arg.is_positional() {
        facts.push(format!("Default `{}`.", defaults.join(" ")));
    }
    if let Some(env) = arg.get_env() {
        facts.push(format!("Environment `{}`.", env.to_string_lossy()));
    }
    if arg.is_required_set() {
        facts.push("Required.".to_string());
    }
    if !facts.is_empty() {
        let _ = writeln!(out, "\n  {}", facts.join(" "));
    }
    out.push('\n');
}

// ---- the keys ----

fn keys() -> String {
    let mut out = header("Keys", "`src/control/keymap.rs` (`HELP`)");
    out.push_str(
        "The page's keys, as its help overlay (`?`) lists them. The setup screens and the \
         installation check say their own keys at the foot of their screens. A key that \
         runs a motor runs it only while held, and any other key stops it.\n\n",
    );
    out.push_str("| key | does |\n|---|---|\n");
    for (key, does) in keymap::HELP {
        let keys: Vec<String> = key.split("  ").map(|k| format!("`{}`", k.trim())).collect();
        let _ = writeln!(out, "| {} | {} |", keys.join(" "), cell(does));
    }
    out
}

// ---- configuration ----

/// Every argument of the command line and its subcommands, the page's first.
fn all_arguments(cmd: &clap::Command) -> Vec<Arg> {
    let mut found: Vec<Arg> = cmd.get_arguments().cloned().collect();
    for sub in cmd.get_subcommands() {
        found.extend(all_arguments(sub));
    }
    found
}

fn configuration() -> String {
    let mut cmd = Cli::command();
    cmd.build();
    let args = all_arguments(&cmd);
    let mut out = header(
        "Configuration keys and environment variables",
        "the config file's keys (`src/settings/file.rs`) and clap's definitions",
    );
    let _ = writeln!(
        out,
        "Each setting is taken from the first of: the option on the command line, its \
         environment variable, the config file, the default. The config file is \
         `config.toml` in the OS's configuration folder, or the file `{}` names; \
         `vpx-efis config` prints its path and every effective value with where it came \
         from.\n",
        settings::CONFIG_ENV
    );
    out.push_str(
        "| key | option | environment | default | what it sets |\n|---|---|---|---|---|\n",
    );
    for key in settings::KEYS {
        let long = key.replace('_', "-");
        let arg = args
            .iter()
            .find(|a| a.get_long() == Some(long.as_str()))
            .unwrap_or_else(|| panic!("config key {key} has no option --{long}"));
        let env = arg
            .get_env()
            .map(|e| format!("`{}`", e.to_string_lossy()))
            .unwrap_or_else(|| "—".into());
        let default = arg
            .get_default_values()
            .iter()
            .map(|d| format!("`{}`", d.to_string_lossy()))
            .collect::<Vec<_>>()
            .join(" ");
        let default = if default.is_empty() {
            "—".into()
        } else {
            default
        };
        let help = arg.get_help().map(|h| h.to_string()).unwrap_or_default();
        let _ = writeln!(
            out,
            "| `{key}` | `--{long}` | {env} | {default} | {} |",
            cell(help.trim())
        );
    }
    out.push_str("\nEnvironment variables:\n\n");
    let mut envs: Vec<(String, String)> = args
        .iter()
        .filter_map(|a| {
            let env = a.get_env()?.to_string_lossy().into_owned();
            Some((env, format!("`--{}`", a.get_long()?)))
        })
        .collect();
    envs.sort();
    envs.dedup();
    let _ = writeln!(
        out,
        "- `{}`: the config file's path, instead of the OS's configuration folder",
        settings::CONFIG_ENV
    );
    for (env, option) in envs {
        let _ = writeln!(out, "- `{env}`: as {option}");
    }
    out
}

// ---- the HTTP API ----

fn http_api() -> String {
    let mut out = header(
        "The remote's HTTP API",
        "`src/remote/routes.rs` (held to the server's router by its test)",
    );
    let _ = writeln!(
        out,
        "The walk-around remote's routes (see [The walk-around remote](../remote.md)). All \
         JSON; amps in amperes and volts in volts, as numbers.\n\n{}\n",
        routes::GATE
    );
    out.push_str("| method | path | body | answers |\n|---|---|---|---|\n");
    for r in routes::ROUTES {
        let body = if r.body.is_empty() { "—" } else { r.body };
        let _ = writeln!(
            out,
            "| {} | `{}` | {} | {} |",
            r.method,
            r.path,
            cell(body),
            cell(r.answers)
        );
    }
    out
}

// ---- exit codes ----

fn exit_codes() -> String {
    let mut out = header("Exit codes", "`src/program.rs` (`exit::MEANINGS`)");
    out.push_str("| code | meaning |\n|---|---|\n");
    for (code, meaning) in exit::MEANINGS {
        let _ = writeln!(out, "| {code} | {} |", cell(meaning));
    }
    out
}

// ---- fault codes ----

fn fault_codes() -> String {
    let mut out = header(
        "Fault codes (ICD Appendix E)",
        "the codec's ICD Table 43 (`crates/vpx-protocol/src/fault.rs`) and \
         `src/check/advice.rs`",
    );
    out.push_str(
        "A faulted circuit shows FAULT and the fault's name on the page. What the unit \
         does and how the fault clears are the ICD's words (Table 43); what to do is \
         ours. A reset is `r` on the circuit's row (`R` for the system fault). A circuit \
         that faults again after a reset is not reset by a second `r`: find the cause \
         first (`Y` sends it anyway).\n\n",
    );
    for row in FAULT_TABLE {
        if row.name == "RESERVED" {
            continue;
        }
        let _ = writeln!(out, "## {}\n", row.name);
        let _ = writeln!(
            out,
            "Code `{:#04x}`. {}\n",
            row.code,
            prose(row.description)
        );
        if row.code == 0 {
            continue;
        }
        let _ = writeln!(out, "- **The unit:** {}", prose(row.action));
        let _ = writeln!(out, "- **It clears:** {}", prose(row.clears));
        if let Some(todo) = advice::what_to_do(FaultCode::from_byte(row.code)) {
            let _ = writeln!(out, "- **What to do:** {}", prose(todo));
        }
        out.push('\n');
    }
    let reserved: Vec<String> = FAULT_TABLE
        .iter()
        .filter(|r| r.name == "RESERVED")
        .map(|r| format!("`{:#04x}`", r.code))
        .collect();
    let _ = writeln!(
        out,
        "## Any other code\n\nThe page shows `FAULT 0x..` with the number. {} are RESERVED in \
         Table 43; anything above `{:#04x}` is not listed.\n\n- **What to do:** {}",
        reserved.join(", "),
        FAULT_TABLE.len() - 1,
        prose(advice::what_to_do(FaultCode::Unknown(0xFF)).unwrap_or(""))
    );
    out
}

// ---- the virtual unit's console ----

fn sim_console() -> String {
    let mut out = header(
        "The virtual VP-X's console",
        "`src/sim/console.rs` (`HELP`)",
    );
    out.push_str(
        "`vpx-efis sim` reads these lines on its standard input, to work the cockpit as a \
         person would (see [The virtual VP-X](../virtual-vpx.md)). `DEVICE` is a device id \
         (0–30) as the ICD's Appendix B numbers them.\n\n",
    );
    let _ = writeln!(out, "```text\n{}\n```", console::HELP);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn markdown_prose_escapes_html_outside_code_only() {
        assert_eq!(prose("a <b> `<c>` *d*"), "a &lt;b&gt; `<c>` \\*d\\*");
        assert_eq!(cell("a|b\nc"), "a\\|b c");
    }
}
