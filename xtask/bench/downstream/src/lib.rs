//! Empty: the benchmark is `benches/downstream.rs`.
