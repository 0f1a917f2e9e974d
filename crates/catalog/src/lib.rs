//! The command catalog of code_aster 17.
