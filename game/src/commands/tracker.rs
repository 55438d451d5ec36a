//! `lightcone tracker ARGS`: the simulated head tracker (publisher).

use std::process::ExitCode;

use lightcone_tracker::publish;

/// Publishes until the duration or count runs out (or forever).
pub fn run(args: Vec<String>) -> ExitCode {
    if args.iter().any(|a| a == "--help" || a == "-h") {
        println!("lightcone tracker {}", publish::USAGE);
        return ExitCode::SUCCESS;
    }
    let args = match publish::parse_args(args) {
        Ok(a) => a,
        Err(e) => {
            eprintln!("lightcone tracker: {e}");
            return ExitCode::from(2);
        }
    };
    match publish::run(args) {
        Ok(_) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("lightcone tracker: {e}");
            ExitCode::FAILURE
        }
    }
}
