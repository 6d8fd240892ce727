use crate::cli::SimArgs;

pub fn run(_args: SimArgs) -> anyhow::Result<()> {
    anyhow::bail!("`sim` is not built yet")
}
