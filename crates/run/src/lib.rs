//! The semantic layer: turns validated commands into a model and results.
