//! Project automation: `cargo xtask ci | docs | bench | demo`.

fn main() {}
