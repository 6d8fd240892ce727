//! `vpx-efis sim --pty | --tcp ADDR:PORT`: the virtual VP-X as a second process, for a
//! page (or any program) to open as a serial port: on a pseudo-terminal (Unix), or on
//! TCP as a serial-to-network bridge offers one (every OS). The path, or
//! `tcp://HOST:PORT`, is the first line on standard output; everything else goes to
//! standard error. Standard input takes the hands of a person in the cockpit, one
//! line at a time (`switch 3 on`, `flip 3`, `help`: see `sim::console`). Runs until
//! killed, also after standard input ends. The line is paced at a real cable's 5760
//! bytes a second each way (`sim::line_rate`) unless `--no-pace` is given.

use std::io::{BufRead, Read, Write};
use std::net::TcpListener;
use std::path::PathBuf;

use anyhow::Context;
use clap::Args;

use crate::link::{PortAddr, open_pty_unit, serve_line};
use crate::program::UsageError;
use crate::sim::console::{self, ConsoleLine};
use crate::sim::{self, SimOptions};

#[derive(Debug, Args)]
pub struct SimArgs {
    /// Create a pseudo-terminal and print its path as the first line on stdout (Unix).
    #[arg(long, conflicts_with = "tcp")]
    pub pty: bool,
    /// Serve the unit on TCP, one client at a time (e.g. 127.0.0.1:5760; port 0 picks a
    /// free one); the bound address is the first line on stdout, as tcp://HOST:PORT.
    #[arg(long, value_name = "ADDR:PORT")]
    pub tcp: Option<std::net::SocketAddr>,
    /// Persist settings to this file (written atomically), like the unit's EEPROM.
    #[arg(long, value_name = "FILE")]
    pub eeprom: Option<PathBuf>,
    /// Scenario: a name under assets/scenarios or a TOML file.
    #[arg(long, default_value = "demo", value_name = "NAME|FILE")]
    pub scenario: String,
    /// Send and take bytes as fast as the pty or socket goes, instead of at the real
    /// line's 5760 bytes a second (57600 baud, 8N1) each way.
    #[arg(long)]
    pub no_pace: bool,
}

pub fn run(args: SimArgs) -> anyhow::Result<()> {
    if !args.pty && args.tcp.is_none() {
        return Err(UsageError(
            "say where the virtual VP-X should be: `vpx-efis sim --pty` (a pseudo-terminal, \
             Unix) or `vpx-efis sim --tcp 127.0.0.1:0` (TCP, any OS; port 0 picks a free one)"
                .into(),
        )
        .into());
    }
    let scenario = sim::load_scenario(&args.scenario)?;
    let mut options = SimOptions::new(scenario);
    options.eeprom = args.eeprom.clone();
    options.log_to_stderr = true;
    if !args.no_pace {
        options = options.paced();
    }
    let eeprom = args
        .eeprom
        .as_ref()
        .map(|p| format!(", EEPROM in {}", p.display()))
        .unwrap_or_default();

    let line = match args.tcp {
        Some(addr) => tcp_line(addr)?,
        None => pty_line()?,
    };
    let shown = line.shown.clone();
    {
        // The first line is the contract with scripts and tests: flush it now.
        let mut out = std::io::stdout().lock();
        writeln!(out, "{shown}").context("cannot write to standard output")?;
        out.flush().context("cannot write to standard output")?;
    }
    eprintln!(
        "vpx-efis sim: scenario {:?} on {shown}{}{}{eeprom}",
        args.scenario,
        if args.tcp.is_some() {
            " (one client at a time)"
        } else {
            " (57600 8N1)"
        },
        if args.no_pace {
            ", not paced"
        } else {
            ", paced at 5760 bytes/s"
        }
    );
    let handle = sim::spawn(options, line.reader, line.writer);
    eprintln!("vpx-efis sim: type `help` for the switches and faults you can work by hand");
    console(&handle);
    // Standard input ended (a script's </dev/null): the unit carries on until killed.
    loop {
        std::thread::sleep(std::time::Duration::from_secs(3600));
        let _ = (&handle, &line.keep);
    }
}

/// Reads standard input line by line and does what each says to the unit, until
/// it ends. Answers go to standard error, as every other word from the sim does.
fn console(handle: &sim::SimHandle) {
    for line in std::io::stdin().lock().lines() {
        let Ok(line) = line else {
            return;
        };
        match console::parse_line(&line) {
            Ok(ConsoleLine::Nothing) => {}
            Ok(ConsoleLine::Help) => eprintln!("{}", console::HELP),
            Ok(ConsoleLine::Command(cmd)) => {
                eprintln!("vpx-efis sim: {}", line.trim());
                handle.inject(cmd);
            }
            Err(e) => eprintln!("vpx-efis sim: {e}"),
        }
    }
}

/// The unit's end of its line, and the name a page opens it by.
struct Line {
    reader: Box<dyn Read + Send>,
    writer: Box<dyn Write + Send>,
    shown: String,
    /// Whatever must stay open as long as the unit runs.
    keep: Box<dyn std::any::Any>,
}

fn tcp_line(addr: std::net::SocketAddr) -> anyhow::Result<Line> {
    let listener =
        TcpListener::bind(addr).with_context(|| format!("cannot listen on TCP {addr}"))?;
    let line = serve_line(listener, |l| eprintln!("vpx-efis sim: {l}"))
        .context("cannot start serving TCP")?;
    let shown = PortAddr::Tcp {
        host: line.local_addr.ip().to_string(),
        port: line.local_addr.port(),
    }
    .to_string();
    Ok(Line {
        reader: Box::new(line.reader),
        writer: Box::new(line.writer),
        shown,
        keep: Box::new(()),
    })
}

/// A pseudo-terminal; where there are none (Windows) this says to use `--tcp`.
fn pty_line() -> anyhow::Result<Line> {
    let pty = open_pty_unit()?;
    Ok(Line {
        reader: pty.reader,
        writer: pty.writer,
        shown: pty.path,
        keep: pty.keep_open,
    })
}
