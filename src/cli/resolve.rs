//! Config resolution: what the command line left at its default is filled from the
//! config file, and where each value came from is noted for `vpx-efis config`.

use std::net::Ipv4Addr;

use clap::ArgMatches;
use clap::parser::ValueSource;

use crate::cli::Command;
use crate::cmd::common::{LogbookArgs, PortArgs, XfspArgs};
use crate::cmd::config::Effective;
use crate::cmd::flash::FlashPortArgs;
use crate::cmd::page::PageArgs;
use crate::link::PortAddr;
use crate::program::UsageError;
use crate::settings::values::Theme as Requested;
use crate::settings::{
    self, BAUD_ENV, Origin, PORT_ENV, Setting, XFSP_CONTROL_ENV, XFSP_CONTROL_FROM_ENV, values,
};

/// A file's setting as the value of a flag that may be absent (`--port`,
/// `--repeat-delay`).
fn optional<T: Clone>(s: &Option<Setting<T>>) -> Option<Setting<Option<T>>> {
    s.clone().map(|s| Setting {
        value: Some(s.value),
        line: s.line,
    })
}

/// Fills what the command line left at its default from the config file, and notes
/// where each value came from. Flags and environment variables (clap's) come first.
struct Resolver<'a> {
    m: &'a ArgMatches,
    file: &'a settings::SettingsFile,
    report: Vec<Effective>,
}

impl Resolver<'_> {
    /// Flag or environment, if the value came from either.
    fn explicit(&self, id: &str, env: Option<&'static str>) -> Option<Origin> {
        // A setting with no flag (yet) can only come from the file or its default.
        self.m.try_contains_id(id).ok()?;
        match self.m.value_source(id) {
            Some(ValueSource::CommandLine) => Some(Origin::Flag),
            Some(ValueSource::EnvVariable) => Some(Origin::Env(env.unwrap_or("?"))),
            _ => None,
        }
    }

    fn pick<T: Clone>(
        &mut self,
        key: &'static str,
        id: &str,
        env: Option<&'static str>,
        value: &mut T,
        file: &Option<Setting<T>>,
        show: impl Fn(&T) -> String,
    ) {
        let origin = match (self.explicit(id, env), file) {
            (Some(o), _) => o,
            (None, Some(s)) => {
                *value = s.value.clone();
                Origin::File { line: s.line }
            }
            (None, None) => Origin::Default,
        };
        self.report.push(Effective {
            key,
            value: show(value),
            origin,
        });
    }

    /// `--port`, `--sim` and `--baud`. `--sim` wins over a port from the environment or
    /// the file; against a `--port` flag it is a contradiction.
    fn port(&mut self, p: &mut PortArgs) -> Result<(), UsageError> {
        if p.sim && self.m.value_source("port") == Some(ValueSource::CommandLine) {
            return Err(UsageError(
                "--port and --sim contradict each other: give one".into(),
            ));
        }
        let file = optional(&self.file.port);
        self.pick("port", "port", Some(PORT_ENV), &mut p.port, &file, |_| {
            String::new()
        });
        let e = self.report.last_mut().expect("just pushed");
        if p.sim {
            p.port = None;
            e.origin = Origin::Flag;
        }
        e.value = match &p.port {
            Some(a) => a.to_string(),
            None => "none: the built-in virtual VP-X".into(),
        };
        self.baud(&mut p.baud);
        Ok(())
    }

    fn flash_port(&mut self, p: &mut FlashPortArgs) {
        let file = optional(&self.file.port);
        self.pick("port", "port", Some(PORT_ENV), &mut p.port, &file, |a| {
            a.as_ref()
                .map_or_else(|| "none".into(), PortAddr::to_string)
        });
        self.baud(&mut p.baud);
    }

    /// `--baud` (or its environment variable), or the file's `baud`.
    fn baud(&mut self, baud: &mut u32) {
        let file = self.file.baud.clone();
        self.pick("baud", "baud", Some(BAUD_ENV), baud, &file, u32::to_string);
    }

    /// `--xfsp` without a value takes the file's group; so does `gateway` (always on
    /// the network). The other XFSp options are filled like any setting.
    fn xfsp(&mut self, x: &mut XfspArgs, always_on: bool) {
        let (group, origin) = match (&x.xfsp, &self.file.xfsp) {
            (Some(Some(g)), _) => (g.clone(), Origin::Flag),
            (_, Some(f)) => (f.value.clone(), Origin::File { line: f.line }),
            _ => (
                crate::xfsp::net::DEFAULT_TARGET.to_string(),
                Origin::Default,
            ),
        };
        if always_on || x.xfsp.is_some() {
            x.xfsp = Some(Some(group.clone()));
        }
        self.report.push(Effective {
            key: "xfsp",
            value: group,
            origin,
        });
        self.pick(
            "xfsp_iface",
            "xfsp_iface",
            None,
            &mut x.xfsp_iface,
            &self.file.xfsp_iface.clone(),
            Ipv4Addr::to_string,
        );
        self.pick(
            "xfsp_source_id",
            "xfsp_source_id",
            None,
            &mut x.xfsp_source_id,
            &self.file.xfsp_source_id.clone(),
            |id| format!("{id:#06x}"),
        );
        self.pick(
            "xfsp_cert",
            "xfsp_cert",
            None,
            &mut x.xfsp_cert,
            &self.file.xfsp_cert.clone(),
            u8::to_string,
        );
        self.pick(
            "xfsp_control",
            "xfsp_control",
            Some(XFSP_CONTROL_ENV),
            &mut x.xfsp_control,
            &self.file.xfsp_control.clone(),
            |on| {
                if *on {
                    "on: takes commands from the network"
                } else {
                    "off"
                }
                .to_string()
            },
        );
        let from = optional(&self.file.xfsp_control_from);
        self.pick(
            "xfsp_control_from",
            "xfsp_control_from",
            Some(XFSP_CONTROL_FROM_ENV),
            &mut x.xfsp_control_from,
            &from,
            |l| {
                l.as_ref()
                    .map_or_else(|| "any source".into(), |l| l.to_string())
            },
        );
    }

    /// `--logbook` and `--aircraft` (or their environment variables), or the file's
    /// `logbook` (a relative path from the config file's folder) and `aircraft`.
    fn logbook(&mut self, l: &mut LogbookArgs, config: Option<&std::path::Path>) {
        let file = self.file.logbook.clone().map(|s| Setting {
            value: Some(match config.and_then(std::path::Path::parent) {
                Some(dir) if s.value.is_relative() => dir.join(&s.value),
                _ => s.value,
            }),
            line: s.line,
        });
        self.pick(
            "logbook",
            "logbook",
            Some(settings::LOGBOOK_ENV),
            &mut l.logbook,
            &file,
            |p| match p {
                Some(p) => p.display().to_string(),
                None => crate::places::logbook_path().map_or_else(
                    || "none: this system has no configuration folder".into(),
                    |p| p.display().to_string(),
                ),
            },
        );
        let aircraft = optional(&self.file.aircraft);
        self.pick(
            "aircraft",
            "aircraft",
            Some(settings::AIRCRAFT_ENV),
            &mut l.aircraft,
            &aircraft,
            |a| {
                a.clone()
                    .unwrap_or_else(|| "not named: records go under the unit".into())
            },
        );
    }

    /// `--theme`, or the file's `theme`.
    fn theme(&mut self, theme: &mut Requested) {
        let file = self.file.theme.clone();
        self.pick("theme", "theme", None, theme, &file, |t| {
            values::theme_word(*t).to_string()
        });
    }

    /// `--repeat-delay`, or the file's `repeat_delay` (checked by the page).
    fn repeat_delay(&mut self, d: &mut Option<u64>) {
        let delay = optional(&self.file.repeat_delay_ms);
        self.pick("repeat_delay", "repeat_delay", None, d, &delay, |d| {
            d.map_or_else(
                || "learned from the terminal".into(),
                |ms| format!("{ms} ms"),
            )
        });
    }
}

/// Reads the config file and applies it to the commands that use it.
pub fn resolve(
    command: &mut Option<Command>,
    page: &mut PageArgs,
    logbook: &mut LogbookArgs,
    matches: &ArgMatches,
) -> anyhow::Result<Vec<Effective>> {
    resolve_with(command, page, logbook, matches, settings::load)
}

/// [`resolve`] with the config file read by `load` (tests give one directly).
fn resolve_with(
    command: &mut Option<Command>,
    page: &mut PageArgs,
    logbook: &mut LogbookArgs,
    matches: &ArgMatches,
    load: impl FnOnce() -> Result<settings::Loaded, crate::toml_lines::FileError>,
) -> anyhow::Result<Vec<Effective>> {
    let uses_settings = matches!(
        command,
        None | Some(
            Command::Backup(_)
                | Command::Check(_)
                | Command::Wires(_)
                | Command::Restore(_)
                | Command::Flash(_)
                | Command::Gateway(_)
                | Command::Config(_)
                | Command::Log(_)
        )
    );
    if !uses_settings {
        return Ok(Vec::new());
    }
    let loaded = load().map_err(|e| UsageError(e.to_string()))?;
    let m = matches.subcommand().map_or(matches, |(_, m)| m);
    let mut r = Resolver {
        m,
        file: &loaded.file,
        report: Vec::new(),
    };
    match command {
        None => {
            if page.replay.is_some() {
                if m.value_source("port") == Some(ValueSource::CommandLine) {
                    return Err(UsageError("--replay and --port contradict each other: a replay is read-only and needs no unit".into()).into());
                }
                page.link.port.port = None;
            } else {
                r.port(&mut page.link.port)?;
            }
            r.xfsp(&mut page.link.xfsp, false);
            r.theme(&mut page.theme);
            r.repeat_delay(&mut page.repeat_delay);
        }
        Some(Command::Backup(a)) => r.port(&mut a.port)?,
        Some(Command::Check(a)) => r.port(&mut a.port)?,
        Some(Command::Wires(a)) => r.port(&mut a.port)?,
        Some(Command::Restore(a)) => r.port(&mut a.port)?,
        Some(Command::Flash(a)) => r.flash_port(&mut a.port),
        Some(Command::Gateway(a)) => {
            r.port(&mut a.link.port)?;
            r.xfsp(&mut a.link.xfsp, true);
        }
        Some(Command::Config(a)) => {
            r.port(&mut a.port)?;
            r.xfsp(&mut a.xfsp, false);
            r.theme(&mut a.theme);
            r.repeat_delay(&mut a.repeat_delay);
        }
        _ => {}
    }
    r.logbook(logbook, loaded.path.as_deref());
    let mut report = r.report;
    if let Some(Command::Config(_)) = command {
        report.insert(
            0,
            Effective {
                key: "config file",
                value: match (&loaded.path, loaded.exists) {
                    (Some(p), true) => p.display().to_string(),
                    (Some(p), false) => format!("{} (not there: nothing set)", p.display()),
                    (None, _) => "(this system has no configuration folder)".into(),
                },
                origin: if std::env::var_os(settings::CONFIG_ENV).is_some_and(|v| !v.is_empty()) {
                    Origin::Env(settings::CONFIG_ENV)
                } else {
                    Origin::Default
                },
            },
        );
    }
    Ok(report)
}

#[cfg(test)]
mod tests {
    use clap::{CommandFactory, FromArgMatches};

    use super::*;
    use crate::cli::Cli;

    /// The page's options after the command line `args` and a config file `text`.
    fn page_with(args: &[&str], text: &str) -> anyhow::Result<crate::app::PageOptions> {
        let m = Cli::command().try_get_matches_from(args)?;
        let mut cli = Cli::from_arg_matches(&m)?;
        let file = settings::parse(text).expect("a good file");
        resolve_with(
            &mut cli.command,
            &mut cli.page,
            &mut cli.logbook,
            &m,
            || {
                Ok(settings::Loaded {
                    path: None,
                    exists: true,
                    file,
                })
            },
        )?;
        Ok(cli.page.into())
    }

    #[test]
    fn the_file_fills_what_the_command_line_left_to_its_default() {
        let file = "port = \"tcp://10.0.0.9:4001\"\nbaud = 115200\ntheme = \"light\"\n\
                    xfsp = \"239.1.1.1:7000\"\nxfsp_iface = \"10.0.0.2\"\nxfsp_source_id = 0x5651\n";
        let p = page_with(&["vpx-efis", "--xfsp"], file).unwrap();
        assert_eq!(p.port, Some("tcp://10.0.0.9:4001".parse().unwrap()));
        assert_eq!(p.baud, 115_200);
        assert_eq!(p.theme, Requested::Light);
        assert_eq!(p.xfsp.xfsp.as_deref(), Some("239.1.1.1:7000"));
        assert_eq!(p.xfsp.xfsp_iface, Ipv4Addr::new(10, 0, 0, 2));
        assert_eq!(p.xfsp.xfsp_source_id, 0x5651);
        assert_eq!(p.repeat_delay, None);
        let with_delay = format!("{file}repeat_delay = 900\n");
        assert_eq!(
            page_with(&["vpx-efis"], &with_delay).unwrap().repeat_delay,
            Some(900)
        );
        assert_eq!(
            page_with(&["vpx-efis", "--repeat-delay", "400"], &with_delay)
                .unwrap()
                .repeat_delay,
            Some(400)
        );

        // Flags win; the file's group is no reason to start bridging.
        let p = page_with(
            &[
                "vpx-efis",
                "--port",
                "/dev/ttyUSB1",
                "--baud",
                "9600",
                "--theme",
                "dark",
            ],
            file,
        )
        .unwrap();
        assert_eq!(p.port, Some(PortAddr::Serial("/dev/ttyUSB1".into())));
        assert_eq!(p.baud, 9600);
        assert_eq!(p.theme, Requested::Dark);
        assert_eq!(p.xfsp.xfsp, None);

        // --sim wins over the file's port; a replay ignores it.
        assert_eq!(page_with(&["vpx-efis", "--sim"], file).unwrap().port, None);
        let replay = page_with(&["vpx-efis", "--replay", "x.vpxcap"], file).unwrap();
        assert_eq!(replay.port, None);
    }

    #[test]
    fn with_no_file_the_defaults_stand() {
        let p = page_with(&["vpx-efis"], "").unwrap();
        assert_eq!(p.port, None);
        assert_eq!(p.baud, 57_600);
        assert_eq!(p.theme, Requested::Auto);
        assert_eq!(p.xfsp.xfsp_source_id, 0x5650);
        let p = page_with(&["vpx-efis", "--xfsp"], "").unwrap();
        assert_eq!(
            p.xfsp.xfsp.as_deref(),
            Some(crate::xfsp::net::DEFAULT_TARGET)
        );
    }

    #[test]
    fn port_and_sim_together_is_a_usage_error() {
        let e = page_with(&["vpx-efis", "--sim", "--port", "COM3"], "").unwrap_err();
        assert!(e.downcast_ref::<UsageError>().is_some(), "{e}");
        assert!(e.to_string().contains("contradict"), "{e}");
    }
}
