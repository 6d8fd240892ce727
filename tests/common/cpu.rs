//! A process's own CPU time, for the idle tests: read from the OS's accounting of
//! that one process, so whatever else loads the machine does not count.

use std::time::{Duration, Instant};

/// How many seconds an idle test measures: `IDLE_CPU_SECS`, else `default`.
pub fn idle_secs(default: u64) -> u64 {
    let asked = std::env::var("IDLE_CPU_SECS").ok();
    asked.and_then(|s| s.parse().ok()).unwrap_or(default)
}

/// The share of a core the running process `pid` uses over the next `secs` seconds.
pub fn share_of_a_core(pid: u32, secs: u64) -> Result<f64, String> {
    let cpu0 = process_cpu_time(pid)?;
    let wall0 = Instant::now();
    std::thread::sleep(Duration::from_secs(secs));
    let cpu = process_cpu_time(pid)? - cpu0;
    Ok(cpu.as_secs_f64() / wall0.elapsed().as_secs_f64())
}

/// User plus system CPU time of a running process, or why it cannot be read here.
#[cfg(target_os = "linux")]
pub fn process_cpu_time(pid: u32) -> Result<Duration, String> {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat"))
        .map_err(|e| format!("/proc/{pid}/stat: {e}"))?;
    // The command name is in parentheses and may hold spaces: count fields after it.
    let rest = stat
        .rfind(')')
        .and_then(|i| stat.get(i + 2..))
        .ok_or_else(|| format!("/proc/{pid}/stat has no command name: {stat:?}"))?;
    let fields: Vec<&str> = rest.split_whitespace().collect();
    // utime and stime are fields 14 and 15 of the whole line, 12 and 13 after comm.
    let ticks = |i: usize| {
        fields
            .get(i)
            .and_then(|f| f.parse::<u64>().ok())
            .ok_or_else(|| format!("/proc/{pid}/stat field {}: {stat:?}", i + 3))
    };
    let ticks = ticks(11)? + ticks(12)?;
    // SAFETY: sysconf has no preconditions.
    let hz = unsafe { libc::sysconf(libc::_SC_CLK_TCK) };
    if hz <= 0 {
        return Err("sysconf(_SC_CLK_TCK) failed".into());
    }
    Ok(Duration::from_secs_f64(ticks as f64 / hz as f64))
}

/// Elsewhere another process's CPU time needs an OS-specific call these tests do not
/// make (getrusage only counts children once they have exited).
#[cfg(not(target_os = "linux"))]
pub fn process_cpu_time(_pid: u32) -> Result<Duration, String> {
    Err("no /proc on this OS to read a running process's CPU time from".into())
}
