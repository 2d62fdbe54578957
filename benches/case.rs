//! Whole-run cost per registered variant at its coarsest ladder step (or loosest tolerance),
//! per case and scene: what one point of the work-precision diagram costs.
fn main() {}
