//! Prints the `gcs solve --set` arguments of one of the check's poses, to solve it with the
//! gcs CLI: `cargo run --release --bin pose -- ur5 7` prints pose 7 of ur5's, and the joint
//! angles it was drawn from on stderr.

fn main() {
    let mut args = std::env::args().skip(1);
    let name = args.next().unwrap_or_else(|| "ur5".to_string());
    let k: usize = args
        .next()
        .map_or(0, |s| s.parse().expect("a pose's index"));
    let arm = gcs_ikgeo::arms::ARMS
        .iter()
        .find(|a| a.name == name)
        .unwrap_or_else(|| panic!("no arm {name}"));
    let pose = gcs_ikgeo::arms::poses(arm, k + 1, gcs_ikgeo::check::seed(arm))[k];
    let names = ["px", "py", "pz", "zx", "zy", "zz", "xx", "xy", "xz"];
    let sets: Vec<String> = names
        .iter()
        .zip(pose.params())
        .map(|(n, x)| format!("--set {n}={x:?}"))
        .collect();
    println!("{}", sets.join(" "));
    eprintln!("drawn from q = {:?}", pose.q);
}
