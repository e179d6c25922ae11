//! The `anysl` binary: the command-line tool of [`anysl_cli`].

fn main() -> std::process::ExitCode {
    anysl_cli::main()
}
