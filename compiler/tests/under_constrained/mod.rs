//! Under-constrained sketches drawn off their constraints, shared by `motion.rs` and the
//! bench's comparison with the baseline's motion (`compiler/bench/tests/motion.rs`).

/// Under-constrained sketches, each drawn off its constraints.
pub const MODELS: [&str; 3] = [
    // A rectangle with its height free, drawn as a leaning quadrilateral.
    "space 2d;
param width = 4;
fixed point O = (0, 0);
segment bottom = (0, 0) -> (4.6, 0.4);
segment right = (4.2, 0.1) -> (3.4, 3.3);
segment top = (4.4, 2.6) -> (-0.3, 3.5);
segment left = (0.2, 3.4) -> (0.3, -0.2);
coincident(bottom.start, O);
coincident(bottom.end, right.start);
coincident(right.end, top.start);
coincident(top.end, left.start);
coincident(left.end, bottom.start);
horizontal(bottom); horizontal(top); vertical(left); vertical(right);
length(bottom) = width;
",
    // A four-bar with no drive (mobility 1), its coupler drawn too long.
    "space 2d;
fixed point A = (0, 0);
fixed point D = (4, 0);
point B = (0.3, 1.4);
point C = (4.6, 2.6);
distance(A, B) = 1.5;
distance(B, C) = 4;
distance(C, D) = 2.5;
",
    // Two free points on a fixed circle at a given distance (mobility 1), drawn off it.
    "space 2d;
fixed circle K = center (0, 0) radius 3;
point P = (3.4, 0.5);
point Q = (1.2, 3.6);
on(P, K);
on(Q, K);
distance(P, Q) = 3;
",
];
