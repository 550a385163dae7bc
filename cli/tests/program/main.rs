//! The `rastty` program end to end, in one test binary: the command line,
//! hostile files, the files a model names, pictures and recordings, and
//! `spin` in a pseudo-terminal. (Peak memory is measured in a binary of
//! its own, `memory.rs`, where no other test's threads share the process.)

#[path = "../../../tests/common/mod.rs"]
mod common;
#[path = "../support/run.rs"]
mod support;

mod cli;
mod hostile;
mod model_files;
mod share;
mod spin;
mod pixels;
