//! Fields as the runner stores them: nodal fields (`cham_no`: DEPL,
//! FORC_NODA…) and element fields (`cham_elem`: SIEF_ELGA at Gauss points,
//! SIGM_ELNO at cell nodes…).
//!
//! Each field is held flat: its components, one `Vec<f64>` of values
//! (a row of components per node or per point) and an index of its nodes
//! or cells, not a vector per node, cell or point.

use aster_mesh::{CellId, NodeId};
use std::collections::BTreeMap;
use std::rc::Rc;

/// The bits of a nodal field's absent value: a quiet NaN with a payload no
/// arithmetic produces (operations give the canonical NaN or an operand's),
/// so that an absent component (`None`) stays apart from a NaN value.
const ABSENT: u64 = 0x7ff8_0000_dead_beef;

fn absent() -> f64 {
    f64::from_bits(ABSENT)
}

fn present(x: f64) -> Option<f64> {
    (x.to_bits() != ABSENT).then_some(x)
}

/// Beyond this many absent rows past the last one, a dense nodal field
/// turns into a list of its nodes.
const DENSE_GAP: usize = 1024;

/// A field on nodes: for the nodes that carry it, one value per component,
/// each present or absent (`None`). A node carries the field when one of
/// its components is present.
///
/// Stored as rows of `components.len()` values, one `Vec<f64>` for all of
/// them: row `i` is node `i` (dense, the usual field on every node of a
/// mesh), or the `i`-th of an ascending node list (a field on a few nodes).
#[derive(Clone, Debug, Default)]
pub struct NodalField {
    components: Vec<String>,
    /// The node of each row, ascending; `None`: row `i` is node `i`.
    nodes: Option<Vec<NodeId>>,
    rows: usize,
    values: Vec<f64>,
}

/// The components of one node of a [`NodalField`], by index.
#[derive(Clone, Copy, Debug)]
pub struct NodeValues<'a>(&'a [f64]);

impl<'a> NodeValues<'a> {
    /// Component `c` (an index into the field's components).
    pub fn get(&self, c: usize) -> Option<f64> {
        self.0.get(c).copied().and_then(present)
    }

    pub fn len(&self) -> usize {
        self.0.len()
    }

    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    pub fn iter(&self) -> impl Iterator<Item = Option<f64>> + 'a {
        self.0.iter().map(|&x| present(x))
    }
}

impl NodalField {
    pub fn new(components: Vec<String>) -> NodalField {
        NodalField {
            components,
            ..NodalField::default()
        }
    }

    /// An empty field laid out for the nodes `0..node_count` (the values
    /// are then set in any order without moving rows).
    pub fn with_node_count(components: Vec<String>, node_count: usize) -> NodalField {
        let n = components.len();
        NodalField {
            components,
            nodes: None,
            rows: node_count,
            values: vec![absent(); node_count * n],
        }
    }

    pub fn components(&self) -> &[String] {
        &self.components
    }

    pub fn component_index(&self, name: &str) -> Option<usize> {
        self.components.iter().position(|c| c == name)
    }

    fn row_of(&self, node: NodeId) -> Option<usize> {
        match &self.nodes {
            None => ((node.0 as usize) < self.rows).then_some(node.0 as usize),
            Some(nodes) => nodes.binary_search(&node).ok(),
        }
    }

    fn row(&self, r: usize) -> &[f64] {
        let n = self.components.len();
        &self.values[r * n..(r + 1) * n]
    }

    /// The row of `node`, added (all absent) if missing.
    fn row_for(&mut self, node: NodeId) -> usize {
        if let Some(r) = self.row_of(node) {
            return r;
        }
        let n = self.components.len();
        let id = node.0 as usize;
        if self.nodes.is_none() && id <= self.rows + DENSE_GAP.max(self.rows) {
            self.values.resize((id + 1) * n, absent());
            self.rows = id + 1;
            return id;
        }
        let rows = self.rows;
        let nodes = self
            .nodes
            .get_or_insert_with(|| (0..rows).map(|i| NodeId(i as u32)).collect());
        let at = nodes.partition_point(|m| *m < node);
        nodes.insert(at, node);
        self.values
            .splice(at * n..at * n, std::iter::repeat_n(absent(), n));
        self.rows += 1;
        at
    }

    fn node_of(&self, r: usize) -> NodeId {
        match &self.nodes {
            None => NodeId(r as u32),
            Some(nodes) => nodes[r],
        }
    }

    /// The components of `node`; `None` when the node carries none.
    pub fn node(&self, node: NodeId) -> Option<NodeValues<'_>> {
        let row = self.row(self.row_of(node)?);
        row.iter()
            .any(|x| x.to_bits() != ABSENT)
            .then_some(NodeValues(row))
    }

    pub fn get(&self, node: NodeId, comp: &str) -> Option<f64> {
        self.get_at(node, self.component_index(comp)?)
    }

    /// Component `c` (an index into the components) of `node`.
    pub fn get_at(&self, node: NodeId, c: usize) -> Option<f64> {
        let r = self.row_of(node)?;
        present(*self.row(r).get(c)?)
    }

    /// One component at every node of a mesh of `node_count` nodes (NaN
    /// where the field lacks it).
    pub fn per_node(&self, comp: &str, node_count: usize) -> Vec<f64> {
        (0..node_count)
            .map(|i| self.get(NodeId(i as u32), comp).unwrap_or(f64::NAN))
            .collect()
    }

    /// The index of component `comp`, added (absent everywhere) if missing.
    fn component_for(&mut self, comp: &str) -> usize {
        if let Some(c) = self.component_index(comp) {
            return c;
        }
        let n = self.components.len();
        let mut values = Vec::with_capacity(self.rows * (n + 1));
        for r in 0..self.rows {
            values.extend_from_slice(&self.values[r * n..(r + 1) * n]);
            values.push(absent());
        }
        self.values = values;
        self.components.push(comp.to_string());
        n
    }

    pub fn set(&mut self, node: NodeId, comp: &str, value: f64) {
        let c = self.component_for(comp);
        self.set_at(node, c, Some(value));
    }

    /// Sets (or, with `None`, removes) component `c` of `node`; `c` must be
    /// an index into the components.
    pub fn set_at(&mut self, node: NodeId, c: usize, value: Option<f64>) {
        let n = self.components.len();
        if c >= n {
            return;
        }
        let r = self.row_for(node);
        self.values[r * n + c] = value.unwrap_or_else(absent);
    }

    /// Sets the components of `node`, in the order of the field's
    /// components (those beyond the given ones absent).
    pub fn insert(&mut self, node: NodeId, values: impl IntoIterator<Item = Option<f64>>) {
        let n = self.components.len();
        let r = self.row_for(node);
        let row = &mut self.values[r * n..(r + 1) * n];
        let mut given = values.into_iter();
        for x in row {
            *x = given.next().flatten().unwrap_or_else(absent);
        }
    }

    /// The nodes that carry the field and their components, by node.
    pub fn iter(&self) -> impl Iterator<Item = (NodeId, NodeValues<'_>)> {
        (0..self.rows).filter_map(move |r| {
            let row = self.row(r);
            row.iter()
                .any(|x| x.to_bits() != ABSENT)
                .then(|| (self.node_of(r), NodeValues(row)))
        })
    }

    /// The nodes that carry the field, ascending.
    pub fn nodes(&self) -> impl Iterator<Item = NodeId> + '_ {
        self.iter().map(|(n, _)| n)
    }

    /// How many nodes carry the field.
    pub fn node_count(&self) -> usize {
        self.iter().count()
    }
}

impl PartialEq for NodalField {
    fn eq(&self, other: &NodalField) -> bool {
        if self.components != other.components {
            return false;
        }
        let (mut a, mut b) = (self.iter(), other.iter());
        loop {
            match (a.next(), b.next()) {
                (None, None) => return true,
                (Some((n, x)), Some((m, y))) if n == m && x.iter().eq(y.iter()) => {}
                _ => return false,
            }
        }
    }
}

/// Where the values of an element field live.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ElemLocation {
    /// `_ELGA`: Gauss points.
    Gauss,
    /// `_ELNO`: the cell's nodes, in the cell's node order.
    Nodes,
    /// `_ELEM`: one value per cell.
    Cell,
}

/// A field on cells: per cell, per point, one value per component. A NaN
/// marks a component the cell's element does not carry (an `ELGA_DEPL_R`
/// field has DX DY on a plane model's faces, DX DY DZ on its edges): it is
/// no value, for reading ([`ElemField::get`]) as for reductions.
///
/// Stored flat: the cells ascending, each cell's first point in `starts`,
/// and one `Vec<f64>` of every point's components, point after point.
#[derive(Clone, Debug, PartialEq)]
pub struct ElemField {
    pub location: ElemLocation,
    components: Vec<String>,
    cells: Vec<CellId>,
    /// Cell `i`'s points are `starts[i]..starts[i + 1]`.
    starts: Vec<usize>,
    values: Vec<f64>,
}

/// The points of one cell of an [`ElemField`], each a slice of one value
/// per component.
#[derive(Clone, Copy, Debug)]
pub struct Points<'a> {
    values: &'a [f64],
    n_comp: usize,
    len: usize,
}

impl<'a> Points<'a> {
    /// How many points.
    pub fn len(&self) -> usize {
        self.len
    }

    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Point `p` (0-based).
    pub fn get(&self, p: usize) -> Option<&'a [f64]> {
        (p < self.len).then(|| &self.values[p * self.n_comp..(p + 1) * self.n_comp])
    }

    pub fn iter(&self) -> impl Iterator<Item = &'a [f64]> + 'a {
        let (values, n) = (self.values, self.n_comp);
        (0..self.len).map(move |p| &values[p * n..(p + 1) * n])
    }

    /// Every value, point after point.
    pub fn flat(&self) -> &'a [f64] {
        self.values
    }
}

impl std::ops::Index<usize> for Points<'_> {
    type Output = [f64];
    fn index(&self, p: usize) -> &[f64] {
        &self.values[p * self.n_comp..(p + 1) * self.n_comp]
    }
}

impl ElemField {
    pub fn new(location: ElemLocation, components: Vec<String>) -> ElemField {
        ElemField {
            location,
            components,
            cells: Vec::new(),
            starts: vec![0],
            values: Vec::new(),
        }
    }

    /// An empty field with room for `cells` cells of `points` points in
    /// all (a field grown by doubling would hold up to twice its values).
    pub fn with_capacity(
        location: ElemLocation,
        components: Vec<String>,
        cells: usize,
        points: usize,
    ) -> ElemField {
        let mut f = ElemField::new(location, components);
        f.cells.reserve_exact(cells);
        f.starts.reserve_exact(cells);
        f.values.reserve_exact(points * f.components.len());
        f
    }

    pub fn components(&self) -> &[String] {
        &self.components
    }

    pub fn component_index(&self, name: &str) -> Option<usize> {
        self.components.iter().position(|c| c == name)
    }

    /// Sets the points of `cell` (each point's values in the order of the
    /// components; missing ones NaN, extra ones dropped).
    pub fn insert<P: AsRef<[f64]>>(&mut self, cell: CellId, points: impl IntoIterator<Item = P>) {
        let n = self.components.len();
        let mut block = Vec::new();
        for p in points {
            let p = p.as_ref();
            block.extend((0..n).map(|c| p.get(c).copied().unwrap_or(f64::NAN)));
        }
        let count = block.len().checked_div(n).unwrap_or(0);
        if self.cells.last().is_none_or(|last| *last < cell) {
            self.cells.push(cell);
            self.values.extend(block);
            self.starts.push(self.starts[self.starts.len() - 1] + count);
            return;
        }
        let at = self.cells.partition_point(|c| *c < cell);
        let start = self.starts[at];
        let (old, shift): (usize, isize) = if self.cells[at] == cell {
            let old = self.starts[at + 1] - start;
            (old, count as isize - old as isize)
        } else {
            self.cells.insert(at, cell);
            self.starts.insert(at + 1, start);
            (0, count as isize)
        };
        self.values.splice(start * n..(start + old) * n, block);
        for s in &mut self.starts[at + 1..] {
            *s = s.wrapping_add_signed(shift);
        }
    }

    /// The points of `cell`; `None` when the field does not cover it.
    pub fn cell(&self, cell: CellId) -> Option<Points<'_>> {
        self.cells.binary_search(&cell).ok().map(|i| self.points(i))
    }

    fn points(&self, i: usize) -> Points<'_> {
        let n = self.components.len();
        let (a, b) = (self.starts[i], self.starts[i + 1]);
        Points {
            values: &self.values[a * n..b * n],
            n_comp: n,
            len: b - a,
        }
    }

    /// The cells the field covers and their points, by cell.
    pub fn iter(&self) -> impl Iterator<Item = (CellId, Points<'_>)> {
        (0..self.cells.len()).map(|i| (self.cells[i], self.points(i)))
    }

    /// The cells the field covers, ascending.
    pub fn cells(&self) -> &[CellId] {
        &self.cells
    }

    /// An `_ELNO` field averaged at the nodes (code_aster's
    /// `MOYE_NOEUD='OUI'`): each node's value is the mean of the values the
    /// cells that carry the field give it. `None` for other locations.
    pub fn nodal_mean(&self, mesh: &aster_mesh::Mesh) -> Option<NodalField> {
        if self.location != ElemLocation::Nodes {
            return None;
        }
        let n = self.components.len();
        let mut sum = vec![0.0; mesh.node_count() * n];
        let mut count = vec![0usize; mesh.node_count()];
        for (cell, points) in self.iter() {
            for (&node, v) in mesh.cell(cell).nodes.iter().zip(points.iter()) {
                let k = node.0 as usize;
                for (acc, x) in sum[k * n..(k + 1) * n].iter_mut().zip(v) {
                    *acc += x;
                }
                count[k] += 1;
            }
        }
        let mut out = NodalField::with_node_count(self.components.clone(), mesh.node_count());
        for (k, &m) in count.iter().enumerate() {
            if m > 0 {
                let row = &sum[k * n..(k + 1) * n];
                out.insert(NodeId(k as u32), row.iter().map(|x| Some(x / m as f64)));
            }
        }
        Some(out)
    }

    /// The field on the cells `keep` accepts only.
    pub fn on_cells(&self, keep: impl Fn(CellId) -> bool) -> ElemField {
        let mut out = ElemField::new(self.location, self.components.clone());
        for (cell, points) in self.iter().filter(|(c, _)| keep(*c)) {
            out.insert(cell, points.iter());
        }
        out
    }

    /// The value at a point (1-based, as `POINT=` counts) of a cell.
    pub fn get(&self, cell: CellId, point: usize, comp: &str) -> Option<f64> {
        let c = self.component_index(comp)?;
        self.cell(cell)?
            .get(point.checked_sub(1)?)?
            .get(c)
            .copied()
            .filter(|v| !v.is_nan())
    }
}

#[derive(Clone, Debug, PartialEq)]
pub enum Field {
    Nodal(NodalField),
    Elem(ElemField),
}

impl Field {
    pub fn components(&self) -> &[String] {
        match self {
            Field::Nodal(f) => &f.components,
            Field::Elem(f) => &f.components,
        }
    }

    /// Every value of a component (all of them if `comp` is `None`), for
    /// `TYPE_TEST` reductions.
    pub fn all_values(&self, comp: Option<&str>) -> Vec<f64> {
        match self {
            Field::Nodal(f) => {
                let idx = comp.and_then(|c| f.component_index(c));
                f.iter()
                    .flat_map(|(_, v)| {
                        v.iter()
                            .enumerate()
                            .filter(move |(i, _)| comp.is_none() || Some(*i) == idx)
                            .filter_map(|(_, x)| x)
                    })
                    .collect()
            }
            Field::Elem(f) => {
                let idx = comp.and_then(|c| f.component_index(c));
                f.iter()
                    .flat_map(|(_, pts)| pts.iter())
                    .flat_map(|v| {
                        v.iter()
                            .enumerate()
                            .filter(move |(i, _)| comp.is_none() || Some(*i) == idx)
                            .map(|(_, x)| *x)
                            .filter(|x| !x.is_nan())
                    })
                    .collect()
            }
        }
    }
}

/// The fields of one stored step, by name (`DEPL`, `SIEF_ELGA`…). Each
/// field is shared (`Rc`): a result copied to add fields (`CALC_CHAMP`
/// with `reuse=`, a `STAT_NON_LINE` continuing a result) copies pointers,
/// not values, and a field is copied only when it is changed
/// ([`StepFields::get_mut`]).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StepFields(BTreeMap<String, Rc<Field>>);

impl StepFields {
    pub fn new() -> StepFields {
        StepFields::default()
    }

    pub fn get(&self, name: &str) -> Option<&Field> {
        self.0.get(name).map(|f| &**f)
    }

    /// The field to change: copied first if another result shares it.
    pub fn get_mut(&mut self, name: &str) -> Option<&mut Field> {
        self.0.get_mut(name).map(Rc::make_mut)
    }

    pub fn insert(&mut self, name: String, field: Field) {
        self.0.insert(name, Rc::new(field));
    }

    pub fn contains_key(&self, name: &str) -> bool {
        self.0.contains_key(name)
    }

    /// Forgets a field (a MACRO_ELAS_MULT case with `OPTION='SANS'` stores
    /// no stresses).
    pub fn remove(&mut self, name: &str) {
        self.0.remove(name);
    }

    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    pub fn keys(&self) -> impl Iterator<Item = &String> {
        self.0.keys()
    }

    pub fn iter(&self) -> impl Iterator<Item = (&String, &Field)> {
        self.0.iter().map(|(k, f)| (k, &**f))
    }

    pub fn iter_mut(&mut self) -> impl Iterator<Item = (&String, &mut Field)> {
        self.0.iter_mut().map(|(k, f)| (k, Rc::make_mut(f)))
    }

    pub fn values_mut(&mut self) -> impl Iterator<Item = &mut Field> {
        self.0.values_mut().map(Rc::make_mut)
    }
}

impl FromIterator<(String, Field)> for StepFields {
    fn from_iter<I: IntoIterator<Item = (String, Field)>>(iter: I) -> StepFields {
        StepFields(iter.into_iter().map(|(k, f)| (k, Rc::new(f))).collect())
    }
}

impl Extend<(String, Field)> for StepFields {
    fn extend<I: IntoIterator<Item = (String, Field)>>(&mut self, iter: I) {
        self.0
            .extend(iter.into_iter().map(|(k, f)| (k, Rc::new(f))));
    }
}

impl<const N: usize> From<[(String, Field); N]> for StepFields {
    fn from(a: [(String, Field); N]) -> StepFields {
        a.into_iter().collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nodal_set_get() {
        let mut f = NodalField::new(vec!["DX".into()]);
        f.set(NodeId(3), "DX", 1.5);
        f.set(NodeId(3), "DY", -2.0);
        f.set(NodeId(1), "DY", 4.0);
        assert_eq!(f.get(NodeId(3), "DX"), Some(1.5));
        assert_eq!(f.get(NodeId(1), "DX"), None);
        assert_eq!(f.get(NodeId(1), "DY"), Some(4.0));
        let all = Field::Nodal(f).all_values(Some("DY"));
        assert_eq!(all, vec![4.0, -2.0]);
    }

    #[test]
    fn nodal_absent_is_not_nan_and_sparse_nodes_keep_order() {
        let mut f = NodalField::new(vec!["DX".into(), "DY".into()]);
        // Far nodes first: the field lists its nodes instead of a dense row
        // per node up to the largest.
        f.set(NodeId(50_000), "DX", 1.0);
        f.set(NodeId(20_000), "DY", f64::NAN);
        f.set(NodeId(30_000), "DX", 3.0);
        f.set_at(NodeId(30_000), 0, None);
        assert_eq!(f.get(NodeId(50_000), "DY"), None);
        assert!(f.get(NodeId(20_000), "DY").is_some_and(f64::is_nan));
        assert_eq!(f.get(NodeId(20_000), "DX"), None);
        // A node whose components are all absent does not carry the field.
        assert!(f.node(NodeId(30_000)).is_none());
        let nodes: Vec<NodeId> = f.nodes().collect();
        assert_eq!(nodes, vec![NodeId(20_000), NodeId(50_000)]);
        assert_eq!(f.values.len(), 3 * 2);
        // A NaN value counts as a value, an absent component does not.
        assert_eq!(Field::Nodal(f.clone()).all_values(Some("DY")).len(), 1);
        let mut g = f.clone();
        assert_ne!(f, g, "a NaN value is not equal to itself");
        g.set(NodeId(20_000), "DY", 0.0);
        f.set(NodeId(20_000), "DY", 0.0);
        assert_eq!(f, g);
    }

    #[test]
    fn nodal_dense_rows_in_any_order() {
        let mut f = NodalField::new(vec!["TEMP".into()]);
        for n in [3, 0, 2] {
            f.set(NodeId(n), "TEMP", n as f64);
        }
        assert!(f.nodes.is_none(), "rows are node numbers");
        let got: Vec<(NodeId, Option<f64>)> = f.iter().map(|(n, v)| (n, v.get(0))).collect();
        assert_eq!(
            got,
            vec![
                (NodeId(0), Some(0.0)),
                (NodeId(2), Some(2.0)),
                (NodeId(3), Some(3.0))
            ]
        );
        // A new component keeps the values of the others.
        f.set(NodeId(2), "FLUX", -1.0);
        assert_eq!(f.get(NodeId(3), "TEMP"), Some(3.0));
        assert_eq!(f.get(NodeId(3), "FLUX"), None);
        assert_eq!(f.get(NodeId(2), "FLUX"), Some(-1.0));
        assert_eq!(f.per_node("FLUX", 3)[2], -1.0);
    }

    #[test]
    fn elem_cells_in_any_order_and_replaced() {
        let comps = vec!["SIXX".to_string(), "SIYY".to_string()];
        let mut f = ElemField::new(ElemLocation::Gauss, comps);
        f.insert(CellId(5), [[1.0, 2.0], [3.0, 4.0]]);
        f.insert(CellId(1), [vec![5.0]]);
        f.insert(CellId(3), [[6.0, 7.0], [8.0, 9.0], [10.0, 11.0]]);
        // Replaced by fewer points: the cells after it move.
        f.insert(CellId(3), [[12.0, 13.0]]);
        assert_eq!(f.cells(), &[CellId(1), CellId(3), CellId(5)]);
        assert_eq!(f.get(CellId(5), 2, "SIYY"), Some(4.0));
        assert_eq!(f.get(CellId(3), 1, "SIXX"), Some(12.0));
        assert_eq!(f.get(CellId(3), 2, "SIXX"), None);
        // A short point is completed with NaN: no value.
        assert_eq!(f.get(CellId(1), 1, "SIYY"), None);
        assert_eq!(f.cell(CellId(5)).map(|p| p.len()), Some(2));
        assert_eq!(
            Field::Elem(f.clone()).all_values(None),
            vec![5.0, 12.0, 13.0, 1.0, 2.0, 3.0, 4.0]
        );
        let kept = f.on_cells(|c| c != CellId(3));
        assert_eq!(kept.cells(), &[CellId(1), CellId(5)]);
        assert_eq!(
            kept.cell(CellId(5)).map(|p| p[1].to_vec()),
            Some(vec![3.0, 4.0])
        );
    }
}
