use crate::cli::FlashArgs;

pub fn run(_args: FlashArgs) -> anyhow::Result<()> {
    anyhow::bail!("`flash` is not built yet")
}
