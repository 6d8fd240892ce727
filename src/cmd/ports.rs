pub fn run() -> anyhow::Result<()> {
    anyhow::bail!("`ports` is not built yet")
}
