//! `CREA_MAILLAGE(CREA_MAILLE=_F(NOM=…, GROUP_MA=…|TOUT='OUI'))` (code_aster's
//! `op0167`): copies of cells, on the same nodes, gathered in a new cell
//! group.

use crate::ops::rebuild::Namer;
use crate::{CellId, Mesh, MeshError};

impl Mesh {
    /// One new cell per selected cell (each once, in increasing cell
    /// number, as code_aster's `getelem` lists them), of the same type and
    /// on the same nodes — no node is created, the copies share the
    /// originals' nodes —, appended after the existing cells and named
    /// `M<number>` from their position (`M<n>_1`… when taken). The copies
    /// form the new cell group `name`; a name already in use is an error
    /// (`MESH1_20`). Occurrences of one command are applied in order, each
    /// appending after the previous one's copies. Returns the copies.
    pub fn copy_cells(&mut self, cells: &[CellId], name: &str) -> Result<Vec<CellId>, MeshError> {
        if self.group_ma(name).is_some() {
            return Err(MeshError::Operation(format!(
                "CREA_MAILLE: the cell group `{name}` already exists (code_aster's MESH1_20): choose another NOM"
            )));
        }
        let mut selected: Vec<CellId> = cells.to_vec();
        selected.sort();
        selected.dedup();
        let mut namer = Namer::new(&self.cell_names, "M");
        let mut made = Vec::with_capacity(selected.len());
        for c in selected {
            let copy = self.cell(c).clone();
            let id = CellId(self.cells.len() as u32);
            let cell_name = namer.name(self.cells.len());
            self.cells.push(copy);
            self.cell_names.push(cell_name);
            made.push(id);
        }
        self.set_group_ma(name, made.clone());
        Ok(made)
    }
}

#[cfg(test)]
mod tests {
    use crate::ops::testmesh::two_quads;
    use crate::{CellId, CellType};

    #[test]
    fn copies_share_nodes_and_form_a_group() {
        let mut m = two_quads();
        let cells_before = m.cells.len();
        let nodes_before = m.node_count();
        // Given out of order and twice: copied once each, in cell order.
        let made = m
            .copy_cells(&[CellId(1), CellId(0), CellId(1)], "COPY")
            .unwrap();
        assert_eq!(made.len(), 2);
        assert_eq!(m.node_count(), nodes_before);
        assert_eq!(m.cells.len(), cells_before + 2);
        assert_eq!(m.cells[cells_before], m.cells[0]);
        assert_eq!(m.cells[cells_before + 1], m.cells[1]);
        assert_eq!(m.cells[cells_before].ty, CellType::QUAD4);
        assert_eq!(m.group_ma("COPY").unwrap().members, made);
        assert_eq!(m.cell_names[cells_before], format!("M{}", cells_before + 1));
        let e = m.copy_cells(&[CellId(0)], "COPY").unwrap_err();
        assert!(e.to_string().contains("MESH1_20"), "{e}");
    }
}
