//! `lightcone-tracker-publisher`: the simulated head tracker as its own
//! small binary (the same as `lightcone tracker`; see
//! [`lightcone_tracker::publish`]).

use std::process::ExitCode;

fn main() -> ExitCode {
    let args = match lightcone_tracker::publish::parse_args(std::env::args().skip(1)) {
        Ok(a) => a,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::from(2);
        }
    };
    match lightcone_tracker::publish::run(args) {
        Ok(_) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("lightcone-tracker-publisher: {e}");
            ExitCode::from(1)
        }
    }
}
