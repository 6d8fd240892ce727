use crate::cli::XfspDumpArgs;

pub fn run(_args: XfspDumpArgs) -> anyhow::Result<()> {
    anyhow::bail!("`xfsp_dump` is not built yet")
}
