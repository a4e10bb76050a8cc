//! `karman`: the command-line interface of the karman rocket flight simulator.

fn main() {}
