//! The `mbdbench` binary: parse the command line and hand it to `cli::execute`.
use clap::Parser;

fn main() {
    // First, before any thread: SIGINT and friends remove the temporary files (`output`).
    mbdbench::output::interrupt::install();
    let cli = match mbdbench::cli::Cli::try_parse() {
        Ok(c) => c,
        Err(e) => {
            let code = if e.use_stderr() {
                mbdbench::cli::EXIT_BAD_INPUT
            } else {
                0
            };
            let _ = e.print();
            std::process::exit(code);
        }
    };
    std::process::exit(mbdbench::cli::execute(cli));
}
