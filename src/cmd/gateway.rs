use crate::cli::GatewayArgs;

pub fn run(_args: GatewayArgs) -> anyhow::Result<()> {
    anyhow::bail!("`gateway` is not built yet")
}
