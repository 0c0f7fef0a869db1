// Misuse of a generated solver: a field the model does not have.

mod solver {
    include!("../generated/fourbar.rs");
}

fn main() {
    let params = solver::Params { crank_length: 2.0, ..Default::default() };
    let _ = solver::solve(&params, &solver::Branches::default(), &solver::Defaults::default());
}
