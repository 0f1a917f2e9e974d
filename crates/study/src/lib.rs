//! Parameter sweeps measuring error against time per method.
