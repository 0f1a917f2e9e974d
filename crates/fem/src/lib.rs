//! Numerics: elements, assembly, linear solves, the incremental Newton
//! solver, kinematic conditions and contact.
