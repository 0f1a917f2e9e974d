//! Contact: pairing of slave points with master cells, gaps and contact conditions.
