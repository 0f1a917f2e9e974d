//! Canonical printer.
