// The codes of the catalog's value types, in the catalog JSON, and the type
// each stands for; the first code of a type is the one written back. Shared
// by `model.rs` and the build script (`include!`d by both).
const TYPE_CODES: &[(&str, ValueType)] = &[
    ("R", ValueType::Real),
    ("I", ValueType::Int),
    ("TXM", ValueType::Text),
    ("C", ValueType::Complex),
    ("grma", ValueType::GroupMa),
    ("grno", ValueType::GroupNo),
    ("ma", ValueType::Cell),
    ("no", ValueType::Node),
    ("CO", ValueType::Co),
    ("UnitDefault", ValueType::Unit),
    ("UnitMed", ValueType::Unit),
    ("not_checked", ValueType::Any),
    ("DataStructure", ValueType::Any),
];
