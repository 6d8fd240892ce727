use crate::cli::DecodeArgs;

pub fn run(_args: DecodeArgs) -> anyhow::Result<()> {
    anyhow::bail!("`decode` is not built yet")
}
