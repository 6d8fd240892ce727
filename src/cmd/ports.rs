//! `vpx-efis ports`: the serial ports this machine has, so a mechanic can find the
//! USB-serial cable's path.

pub fn run() -> anyhow::Result<()> {
    let ports = crate::link::list_ports()?;
    if ports.is_empty() {
        println!(
            "No serial ports found. Plug in the USB-serial cable, or run `vpx-efis sim --pty` for a virtual unit."
        );
        return Ok(());
    }
    for p in ports {
        println!("{:<24} {}", p.path, p.description);
    }
    Ok(())
}
