//! Integration tests of the `karman` binary (one binary; one module per command).

mod check;
mod common;
mod compare;
mod corpus;
mod fit;
mod guide;
mod hostile;
mod import;
mod inspect;
mod log;
mod montecarlo;
mod safety;
mod sensitivity;
mod sil;
mod simulate;
mod solve;
mod sweep;
mod until;
mod weather;
