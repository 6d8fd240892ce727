//! `vpx-efis sim --pty`: the virtual VP-X on a pseudo-terminal, for a page (or any
//! program) to open as a serial port. The slave's path is the first line on standard
//! output; everything else goes to standard error. Runs until killed.

use std::io::Write;

use anyhow::{Context, bail};

use crate::cli::SimArgs;
use crate::link::open_pty_pair;
use crate::sim::{self, SimOptions};

pub fn run(args: SimArgs) -> anyhow::Result<()> {
    if !args.pty {
        bail!("say where the unit should be: `vpx-efis sim --pty` (the only transport so far)");
    }
    let scenario = sim::load_scenario(&args.scenario)?;
    let pty = open_pty_pair()?;
    {
        // The first line is the contract with scripts and tests: flush it now.
        let mut out = std::io::stdout().lock();
        writeln!(out, "{}", pty.path).context("cannot write to standard output")?;
        out.flush().context("cannot write to standard output")?;
    }
    eprintln!(
        "vpx-efis sim: scenario {:?} on {} (57600 8N1){}",
        args.scenario,
        pty.path,
        args.eeprom
            .as_ref()
            .map(|p| format!(", EEPROM in {}", p.display()))
            .unwrap_or_default()
    );
    let reader = pty
        .master
        .try_clone_native()
        .context("cannot clone the pseudo-terminal")?;
    let mut options = SimOptions::new(scenario);
    options.eeprom = args.eeprom;
    options.log_to_stderr = true;
    let handle = sim::spawn(options, Box::new(reader), Box::new(pty.master));
    // Kept open so the master never sees end-of-file when a page closes its end.
    let _slave = pty.slave;
    loop {
        std::thread::sleep(std::time::Duration::from_secs(3600));
        let _ = &handle;
    }
}
