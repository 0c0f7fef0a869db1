//! How a plan's assemblies are searched, by the interpreter (`crate::all`) and by generated
//! `solve_all` alike: the most branch combinations tried, and the grid of starts of its
//! defaults when the search cannot be exhaustive.

/// The most branch combinations tried.
pub const MAX_COMBINATIONS: usize = 4096;

/// Starting values of each default when the search cannot be exhaustive, for one or two
/// defaults varied ([`grid`]).
pub const GRID: usize = 12;

/// Starting values of each of `varied` defaults in the grid: [`GRID`] for one or two, fewer
/// past that (at least 3), so that the grid stays about `GRID^2` starts (a Stewart platform's
/// three turns: 5 each, 125 starts, not 1,728).
pub fn grid(varied: usize) -> usize {
    if varied <= 2 {
        return GRID;
    }
    let each = ((GRID * GRID) as f64).powf(1.0 / varied as f64).floor() as usize;
    each.max(3)
}
