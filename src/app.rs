//! The wiring: link, model, UI, control and (optionally) the XFSp gateway.

use crate::cli::PageArgs;

pub fn run(_args: PageArgs) -> anyhow::Result<()> {
    anyhow::bail!("the page is not built yet")
}
