//! Prints a member of a generated model family (`gcs_bench::families`) as `.gcs` source,
//! for measuring sizes the examples crate does not keep:
//!
//! ```sh
//! cargo run -p gcs-bench --example family -- fourbar_chain 1024 > fourbar_chain_1024.gcs
//! gcs bench fourbar_chain_1024.gcs --samples 10
//! ```

use gcs_bench::families::Family;
use std::process::ExitCode;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let names: Vec<&str> = Family::ALL.iter().map(|f| f.name()).collect();
    let names = names.join(", ");
    let (Some(name), Some(size)) = (args.first(), args.get(1)) else {
        eprintln!("usage: family NAME N   (NAME: {names})");
        return ExitCode::from(2);
    };
    let Some(family) = Family::named(name) else {
        eprintln!("no family `{name}` ({names})");
        return ExitCode::from(2);
    };
    match size.parse::<usize>() {
        Ok(n) if n > 0 => {
            print!("{}", family.model(n));
            ExitCode::SUCCESS
        }
        _ => {
            eprintln!("N must be a positive whole number, not `{size}`");
            ExitCode::from(2)
        }
    }
}
