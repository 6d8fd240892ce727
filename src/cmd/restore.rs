use crate::cli::RestoreArgs;

pub fn run(_args: RestoreArgs) -> anyhow::Result<()> {
    anyhow::bail!("`restore` is not built yet")
}
