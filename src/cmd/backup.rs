use crate::cli::BackupArgs;

pub fn run(_args: BackupArgs) -> anyhow::Result<()> {
    anyhow::bail!("`backup` is not built yet")
}
