fn main() -> std::process::ExitCode {
    vpx_efis::cli::main()
}
