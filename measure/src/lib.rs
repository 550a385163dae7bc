//! What the measuring programs share: euc drawing the bunny as rastty
//! draws it (`vs_euc`).

pub mod euc_pipeline;
