//! Fields as the runner stores them: nodal fields (`cham_no`: DEPL,
//! FORC_NODA…) and element fields (`cham_elem`: SIEF_ELGA at Gauss points,
//! SIGM_ELNO at cell nodes…).

use aster_mesh::{CellId, NodeId};
use std::collections::BTreeMap;
use std::rc::Rc;

/// A field on nodes: for each node that carries it, one value per
/// component (`None` when that node lacks the component).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct NodalField {
    pub components: Vec<String>,
    pub values: BTreeMap<NodeId, Vec<Option<f64>>>,
}

impl NodalField {
    pub fn new(components: Vec<String>) -> NodalField {
        NodalField {
            components,
            values: BTreeMap::new(),
        }
    }

    pub fn component_index(&self, name: &str) -> Option<usize> {
        self.components.iter().position(|c| c == name)
    }

    pub fn get(&self, node: NodeId, comp: &str) -> Option<f64> {
        let c = self.component_index(comp)?;
        self.values.get(&node)?.get(c).copied().flatten()
    }

    /// One component at every node of a mesh of `node_count` nodes (NaN
    /// where the field lacks it).
    pub fn per_node(&self, comp: &str, node_count: usize) -> Vec<f64> {
        (0..node_count)
            .map(|i| self.get(NodeId(i as u32), comp).unwrap_or(f64::NAN))
            .collect()
    }

    pub fn set(&mut self, node: NodeId, comp: &str, value: f64) {
        let c = match self.component_index(comp) {
            Some(c) => c,
            None => {
                self.components.push(comp.to_string());
                for v in self.values.values_mut() {
                    v.push(None);
                }
                self.components.len() - 1
            }
        };
        let n = self.components.len();
        let slot = self.values.entry(node).or_insert_with(|| vec![None; n]);
        slot[c] = Some(value);
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
#[derive(Clone, Debug, PartialEq)]
pub struct ElemField {
    pub location: ElemLocation,
    pub components: Vec<String>,
    pub values: BTreeMap<CellId, Vec<Vec<f64>>>,
}

impl ElemField {
    pub fn component_index(&self, name: &str) -> Option<usize> {
        self.components.iter().position(|c| c == name)
    }

    /// An `_ELNO` field averaged at the nodes (code_aster's
    /// `MOYE_NOEUD='OUI'`): each node's value is the mean of the values the
    /// cells that carry the field give it. `None` for other locations.
    pub fn nodal_mean(&self, mesh: &aster_mesh::Mesh) -> Option<NodalField> {
        if self.location != ElemLocation::Nodes {
            return None;
        }
        let mut sum: BTreeMap<NodeId, (Vec<f64>, usize)> = BTreeMap::new();
        for (&cell, points) in &self.values {
            for (&node, v) in mesh.cell(cell).nodes.iter().zip(points) {
                let slot = sum
                    .entry(node)
                    .or_insert_with(|| (vec![0.0; self.components.len()], 0));
                for (acc, x) in slot.0.iter_mut().zip(v) {
                    *acc += x;
                }
                slot.1 += 1;
            }
        }
        let mut out = NodalField::new(self.components.clone());
        for (node, (v, n)) in sum {
            out.values
                .insert(node, v.into_iter().map(|x| Some(x / n as f64)).collect());
        }
        Some(out)
    }

    /// The field on the cells `keep` accepts only.
    pub fn on_cells(&self, keep: impl Fn(CellId) -> bool) -> ElemField {
        ElemField {
            location: self.location,
            components: self.components.clone(),
            values: self
                .values
                .iter()
                .filter(|(c, _)| keep(**c))
                .map(|(c, v)| (*c, v.clone()))
                .collect(),
        }
    }

    /// The value at a point (1-based, as `POINT=` counts) of a cell.
    pub fn get(&self, cell: CellId, point: usize, comp: &str) -> Option<f64> {
        let c = self.component_index(comp)?;
        self.values
            .get(&cell)?
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
                f.values
                    .values()
                    .flat_map(|v| {
                        v.iter()
                            .enumerate()
                            .filter(move |(i, _)| comp.is_none() || Some(*i) == idx)
                            .filter_map(|(_, x)| *x)
                    })
                    .collect()
            }
            Field::Elem(f) => {
                let idx = comp.and_then(|c| f.component_index(c));
                f.values
                    .values()
                    .flat_map(|pts| pts.iter())
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
}
