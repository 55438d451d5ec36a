//! `lightcone tracker ARGS`: the simulated head tracker (publisher).

use std::process::ExitCode;

use lightcone_tracker::publish;

/// Publishes until the duration or count runs out, or Ctrl-C (exit 130).
pub fn run(args: Vec<String>) -> ExitCode {
    if args.iter().any(|a| a == "--help" || a == "-h") {
        crate::sayln!("lightcone tracker {}", publish::USAGE);
        return ExitCode::SUCCESS;
    }
    let args = match publish::parse_args(args) {
        Ok(a) => a,
        Err(e) => {
            crate::errln!("lightcone tracker: {e}");
            return ExitCode::from(2);
        }
    };
    crate::interrupt::watch();
    match publish::run_until(args, &crate::interrupt::interrupted) {
        Ok(_) if crate::interrupt::interrupted() => {
            crate::interrupt::exit_code("the tracker stopped publishing")
        }
        Ok(_) => ExitCode::SUCCESS,
        Err(e) => {
            crate::errln!("lightcone tracker: {e}");
            ExitCode::FAILURE
        }
    }
}
