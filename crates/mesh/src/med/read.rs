//! Reading the first (or a named) mesh of a MED file, versions 2.x to 4.x.
//!
//! Layouts:
//! - MED 2.x: `ENS_MAA/<mesh>/{NOE,MAI}` and families under `ENS_MAA/<mesh>/FAS`;
//! - MED 3.x/4.x: a computation-step level `ENS_MAA/<mesh>/<dt><it>/{NOE,MAI}`
//!   and families under `FAS/<mesh>`.
//!
//! Families become groups: each family lists (in `GRO/NOM`, 80 characters a
//! name) the groups its members belong to; node families have positive
//! numbers, cell families negative ones, 0 is "no group". Groups are listed
//! in the order they are first met when walking node families by increasing
//! number and cell families by decreasing number (-1, -2, …), the order
//! MED writers (code_aster, Salome) number families in.

use super::celltypes::{aster_from_med, MED_TYPES};
use crate::error::MeshError;
use crate::hdf5::{H5Error, H5File, Object};
use crate::{Cell, CellId, Group, Mesh, NodeId};
use std::collections::HashMap;
use std::path::Path;

/// What was found in a MED file besides the mesh.
#[derive(Debug, Clone, PartialEq)]
pub struct MedInfo {
    /// (major, minor, release) from `INFOS_GENERALES`, when present.
    pub version: Option<(i64, i64, i64)>,
    /// Names of all meshes in the file, in file order.
    pub meshes: Vec<String>,
    /// The mesh that was read.
    pub mesh_name: String,
    /// What was read but could not be used: nodes or cells whose family
    /// the file does not define (a damaged or missing family header), so
    /// that the groups they belong to are missing.
    pub warnings: Vec<String>,
}

/// Read the first mesh of a MED file.
pub fn read_med(path: &Path) -> Result<Mesh, MeshError> {
    read_med_named(path, None).map(|(m, _)| m)
}

/// Read the mesh `name` (or the first one) of a MED file.
pub fn read_med_named(path: &Path, name: Option<&str>) -> Result<(Mesh, MedInfo), MeshError> {
    let data = std::fs::read(path).map_err(|e| MeshError::Io {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    read_med_bytes(data, path, name)
}

/// Read a MED file image already in memory (`path` is for messages).
pub fn read_med_bytes(
    data: Vec<u8>,
    path: &Path,
    name: Option<&str>,
) -> Result<(Mesh, MedInfo), MeshError> {
    let h5 = |error: H5Error| MeshError::Hdf5 {
        path: path.to_path_buf(),
        error,
    };
    let med = |message: String| MeshError::Med {
        path: path.to_path_buf(),
        message,
    };
    let file = H5File::from_bytes(data).map_err(h5)?;
    let r = Reader { file: &file };
    let version = r.version().map_err(h5)?;
    let ens = file.get("ENS_MAA").map_err(h5)?.ok_or_else(|| {
        med("not a MED mesh file: no `ENS_MAA` group (is it a MED result-only file?)".into())
    })?;
    let meshes: Vec<(String, u64)> = file.links(&ens).map_err(h5)?;
    if meshes.is_empty() {
        return Err(med("the MED file holds no mesh".into()));
    }
    let (mesh_name, mesh_addr) = match name {
        None => meshes[0].clone(),
        Some(n) => meshes
            .iter()
            .find(|(m, _)| m == n)
            .cloned()
            .ok_or_else(|| {
                let names: Vec<&str> = meshes.iter().map(|m| m.0.as_str()).collect();
                med(format!(
                    "no mesh named `{n}` in the file (it has: {}){}",
                    names.join(", "),
                    crate::error::suggest(n, names.iter().copied())
                        .map(|s| format!("; did you mean `{s}`?"))
                        .unwrap_or_default()
                ))
            })?,
    };
    let mesh_obj = file.object_at(mesh_addr).map_err(h5)?;
    let (mesh, warnings) = r.mesh(&mesh_obj, &mesh_name, path).map_err(|e| match e {
        ReadError::H5(e) => h5(e),
        ReadError::Mesh(e) => e,
    })?;
    Ok((
        mesh,
        MedInfo {
            version,
            meshes: meshes.into_iter().map(|m| m.0).collect(),
            mesh_name,
            warnings,
        },
    ))
}

enum ReadError {
    H5(H5Error),
    Mesh(MeshError),
}

impl From<H5Error> for ReadError {
    fn from(e: H5Error) -> Self {
        ReadError::H5(e)
    }
}

struct Reader<'a> {
    file: &'a H5File,
}

/// A family: its number and the groups it stands for.
struct Family {
    num: i64,
    groups: Vec<String>,
}

impl Reader<'_> {
    fn version(&self) -> Result<Option<(i64, i64, i64)>, H5Error> {
        let Some(info) = self.file.get("INFOS_GENERALES")? else {
            return Ok(None);
        };
        let get = |n: &str| -> Result<Option<i64>, H5Error> {
            Ok(self.file.attribute(&info, n)?.and_then(|a| a.as_i64()))
        };
        Ok(match (get("MAJ")?, get("MIN")?, get("REL")?) {
            (Some(a), Some(b), Some(c)) => Some((a, b, c)),
            _ => None,
        })
    }

    fn child(&self, obj: &Object, name: &str) -> Result<Option<Object>, H5Error> {
        self.file.child(obj, name)
    }

    fn attr_i64(&self, obj: &Object, name: &str) -> Result<Option<i64>, H5Error> {
        Ok(self.file.attribute(obj, name)?.and_then(|a| a.as_i64()))
    }

    fn mesh(
        &self,
        mesh_obj: &Object,
        mesh_name: &str,
        path: &Path,
    ) -> Result<(Mesh, Vec<String>), ReadError> {
        let med_err = |message: String| {
            ReadError::Mesh(MeshError::Med {
                path: path.to_path_buf(),
                message,
            })
        };
        if self.attr_i64(mesh_obj, "TYP")?.unwrap_or(0) != 0 {
            return Err(med_err(format!(
                "mesh `{mesh_name}` is a structured MED grid; only unstructured meshes are read"
            )));
        }
        // MED 2 keeps NOE/MAI under the mesh; MED 3+ under a computation step.
        let step = if self.child(mesh_obj, "NOE")?.is_some() {
            mesh_obj.clone()
        } else {
            let mut found = None;
            for (_, addr) in self.file.links(mesh_obj)? {
                let o = self.file.object_at(addr)?;
                if !o.is_dataset() && self.child(&o, "NOE")?.is_some() {
                    found = Some(o);
                    break;
                }
            }
            found.ok_or_else(|| {
                med_err(format!("mesh `{mesh_name}` has no nodes (no `NOE` group)"))
            })?
        };
        let noe = self
            .child(&step, "NOE")?
            .ok_or_else(|| med_err(format!("mesh `{mesh_name}` has no `NOE` group")))?;
        let coo_obj = self
            .child(&noe, "COO")?
            .ok_or_else(|| med_err(format!("mesh `{mesh_name}` has no coordinates (`NOE/COO`)")))?;
        let coo = self.file.read(&coo_obj)?.to_f64()?;
        let space_dim = self
            .attr_i64(mesh_obj, "ESP")?
            .or(self.attr_i64(mesh_obj, "DIM")?)
            .unwrap_or(3);
        let nbr = self.attr_i64(&coo_obj, "NBR")?;
        let (n_nodes, dim) = match nbr {
            Some(n) if n > 0 && coo.len() as i64 % n == 0 => (n as usize, coo.len() / n as usize),
            Some(0) => (0, space_dim.clamp(1, 3) as usize),
            _ if (1..=3).contains(&space_dim) && coo.len() % space_dim as usize == 0 => {
                (coo.len() / space_dim as usize, space_dim as usize)
            }
            _ => {
                return Err(med_err(format!(
                    "mesh `{mesh_name}`: {} coordinates do not fit {space_dim}-D nodes",
                    coo.len()
                )))
            }
        };
        if !(1..=3).contains(&dim) {
            return Err(med_err(format!(
                "mesh `{mesh_name}`: nodes with {dim} coordinates"
            )));
        }
        // MED stores coordinates "no interlace": all x, then all y, then all z.
        let mut coords = vec![[0.0f64; 3]; n_nodes];
        for (k, c) in coords.iter_mut().enumerate() {
            for d in 0..dim {
                c[d] = coo[d * n_nodes + k];
            }
        }
        let node_fam = self.int_dataset(&noe, "FAM", n_nodes)?;

        let mut cells = Vec::new();
        let mut cell_fam: Vec<i64> = Vec::new();
        let mut cell_names: Vec<Option<String>> = Vec::new();
        if let Some(mai) = self.child(&step, "MAI")? {
            let present: Vec<(String, u64)> = self.file.links(&mai)?;
            for (name, _) in &present {
                if !MED_TYPES.iter().any(|t| t.0 == name) {
                    return Err(ReadError::Mesh(MeshError::UnknownCellType {
                        path: path.to_path_buf(),
                        name: name.clone(),
                        suggestion: None,
                    }));
                }
            }
            for (med_name, _, ty) in MED_TYPES {
                let Some((_, addr)) = present.iter().find(|(n, _)| n == med_name) else {
                    continue;
                };
                let tobj = self.file.object_at(*addr)?;
                let Some(nod) = self.child(&tobj, "NOD")? else {
                    continue; // descending connectivity only: not a cell block code_aster reads
                };
                let conn = self.file.read(&nod)?.to_i32_clamped()?;
                let nn = ty.node_count();
                let count = conn.len() / nn;
                if conn.len() % nn != 0 {
                    return Err(med_err(format!(
                        "{med_name} connectivity has {} entries, not a multiple of {nn}",
                        conn.len()
                    )));
                }
                if let Some(at) = conn.iter().position(|&n| n < 1 || n as usize > n_nodes) {
                    return Err(med_err(format!(
                        "{med_name} cell {} refers to node {}, outside 1..{n_nodes}",
                        at % count + 1,
                        conn[at]
                    )));
                }
                // No interlace: node k of every cell, then node k+1…, each
                // a column; code_aster's node j is MED's column perm[j].
                let identity: Vec<usize> = (0..nn).collect();
                let perm = aster_from_med(ty).unwrap_or(&identity);
                let columns: Vec<&[i32]> = perm
                    .iter()
                    .map(|&k| &conn[k * count..(k + 1) * count])
                    .collect();
                cells.reserve(count);
                for i in 0..count {
                    let nodes = columns
                        .iter()
                        .map(|col| NodeId(col[i] as u32 - 1))
                        .collect();
                    cells.push(Cell { ty, nodes });
                }
                cell_fam.extend(self.int_dataset(&tobj, "FAM", count)?);
                match self.names(&tobj, count)? {
                    Some(n) => cell_names.extend(n.into_iter().map(Some)),
                    None => cell_names.extend(std::iter::repeat_n(None, count)),
                }
            }
        }

        let families = self.families(mesh_obj, mesh_name)?;
        let (groups_no, groups_ma, warnings) = build_groups(&families, &node_fam, &cell_fam);

        // code_aster 17 reads no node name from a MED file (its MED
        // reader never fills `.NOMNOE`; `BaseMesh::getNodeName` gives the
        // node's rank): its tables print `783` (ssnv127f filters
        // POST_RELEVE_T rows on NOEUD='783'), also where the file names the
        // nodes — `N5676` (ssnv166a) or `O`, `A`, `N3`… (ssls100b filters
        // NOEUD='1' for the node it names `O`). `N783` still finds node 783
        // (`aster_run::select`).
        let node_names = (1..=n_nodes).map(|i| i.to_string()).collect();
        let cell_names = cell_names
            .into_iter()
            .enumerate()
            .map(|(i, n)| {
                n.filter(|s| !s.is_empty())
                    .unwrap_or_else(|| numbered_name('M', i + 1))
            })
            .collect();
        Ok((
            Mesh {
                dim: dim as u8,
                coords,
                node_names,
                cells,
                cell_names,
                groups_ma,
                groups_no,
            },
            warnings,
        ))
    }

    /// An integer dataset of `n` values (family numbers), zeros when absent.
    fn int_dataset(&self, parent: &Object, name: &str, n: usize) -> Result<Vec<i64>, ReadError> {
        match self.child(parent, name)? {
            Some(o) => {
                let mut v = self.file.read(&o)?.to_i64()?;
                v.resize(n, 0);
                Ok(v)
            }
            None => Ok(vec![0; n]),
        }
    }

    /// Names from a `NOM` dataset (8 characters in MED 2, 16 in MED 3+).
    fn names(&self, parent: &Object, n: usize) -> Result<Option<Vec<String>>, ReadError> {
        let Some(o) = self.child(parent, "NOM")? else {
            return Ok(None);
        };
        if n == 0 {
            return Ok(Some(Vec::new()));
        }
        let data = self.file.read(&o)?;
        let width = data.raw.len() / n;
        if width == 0 {
            return Ok(None);
        }
        let mut names = data.names(width);
        names.truncate(n);
        if names.iter().all(|s| s.is_empty()) {
            return Ok(None);
        }
        Ok(Some(names))
    }

    fn families(&self, mesh_obj: &Object, mesh_name: &str) -> Result<Vec<Family>, ReadError> {
        let fas = match self.child(mesh_obj, "FAS")? {
            Some(f) => Some(f),
            None => match self.file.get("FAS")? {
                Some(root) => self.child(&root, mesh_name)?,
                None => None,
            },
        };
        let mut out = Vec::new();
        if let Some(fas) = fas {
            self.collect_families(&fas, &mut out, 0)?;
        }
        Ok(out)
    }

    /// Families are groups with a `NUM` attribute, possibly under
    /// `NOEUD`/`ELEME` sub-groups.
    fn collect_families(
        &self,
        group: &Object,
        out: &mut Vec<Family>,
        depth: usize,
    ) -> Result<(), ReadError> {
        if depth > 3 {
            return Ok(());
        }
        for (_, addr) in self.file.links(group)? {
            let o = self.file.object_at(addr)?;
            if o.is_dataset() {
                continue;
            }
            match self.attr_i64(&o, "NUM")? {
                Some(num) => {
                    let mut groups = Vec::new();
                    if let Some(gro) = self.child(&o, "GRO")? {
                        if let Some(nom) = self.child(&gro, "NOM")? {
                            let data = self.file.read(&nom)?;
                            let mut names = data.names(80);
                            if let Some(nbr) = self.attr_i64(&gro, "NBR")? {
                                names.truncate(nbr.max(0) as usize);
                            }
                            groups.extend(names.into_iter().filter(|s| !s.is_empty()));
                        }
                    }
                    out.push(Family { num, groups });
                }
                None => self.collect_families(&o, out, depth + 1)?,
            }
        }
        Ok(())
    }
}

/// `N12`, `M7`…: code_aster's default names, built without the
/// formatting machinery (a million of them are made for a big mesh).
pub(crate) fn numbered_name(prefix: char, mut i: usize) -> String {
    let mut digits = [0u8; 20];
    let mut k = digits.len();
    loop {
        k -= 1;
        digits[k] = b'0' + (i % 10) as u8;
        i /= 10;
        if i == 0 {
            break;
        }
    }
    let mut s = String::with_capacity(1 + digits.len() - k);
    s.push(prefix);
    for &d in &digits[k..] {
        s.push(d as char);
    }
    s
}

/// The groups, and a warning per family number that nodes or cells carry
/// but the file does not define.
fn build_groups(
    families: &[Family],
    node_fam: &[i64],
    cell_fam: &[i64],
) -> (Vec<Group<NodeId>>, Vec<Group<CellId>>, Vec<String>) {
    let mut node_families: Vec<&Family> = families.iter().filter(|f| f.num > 0).collect();
    node_families.sort_by_key(|f| f.num);
    let mut cell_families: Vec<&Family> = families.iter().filter(|f| f.num < 0).collect();
    cell_families.sort_by_key(|f| -f.num);
    fn index(fams: &[&Family]) -> (Vec<String>, HashMap<i64, Vec<usize>>) {
        let mut names: Vec<String> = Vec::new();
        let mut pos: HashMap<&str, usize> = HashMap::new();
        let mut of_family = HashMap::new();
        for f in fams {
            let mut ids = Vec::new();
            for g in &f.groups {
                let id = *pos.entry(g.as_str()).or_insert_with(|| {
                    names.push(g.clone());
                    names.len() - 1
                });
                if !ids.contains(&id) {
                    ids.push(id);
                }
            }
            of_family.insert(f.num, ids);
        }
        (names, of_family)
    }
    let (nnames, nfam) = index(&node_families);
    let mut groups_no: Vec<Group<NodeId>> = nnames
        .into_iter()
        .map(|name| Group {
            name,
            members: Vec::new(),
        })
        .collect();
    let nfam = dense(nfam);
    for (i, f) in node_fam.iter().enumerate() {
        for &g in nfam.get(f) {
            groups_no[g].members.push(NodeId(i as u32));
        }
    }
    let (cnames, cfam) = index(&cell_families);
    let mut groups_ma: Vec<Group<CellId>> = cnames
        .into_iter()
        .map(|name| Group {
            name,
            members: Vec::new(),
        })
        .collect();
    let cfam = dense(cfam);
    for (i, f) in cell_fam.iter().enumerate() {
        for &g in cfam.get(f) {
            groups_ma[g].members.push(CellId(i as u32));
        }
    }
    // code_aster creates no empty group.
    groups_no.retain(|g| !g.members.is_empty());
    groups_ma.retain(|g| !g.members.is_empty());
    let mut warnings = undefined_families("node", node_fam, &nfam);
    warnings.extend(undefined_families("cell", cell_fam, &cfam));
    (groups_no, groups_ma, warnings)
}

/// Family numbers (other than 0, "no group") that entities carry but no
/// family header defines, with how many entities carry each.
fn undefined_families(what: &str, fam: &[i64], known: &DenseFamilies) -> Vec<String> {
    let mut missing: std::collections::BTreeMap<i64, usize> = Default::default();
    for &f in fam {
        if f != 0 && !known.defines(f) {
            *missing.entry(f).or_default() += 1;
        }
    }
    missing
        .into_iter()
        .map(|(f, n)| {
            format!(
                "{n} {what}(s) belong to family {f}, which the file does not define (a damaged or missing family header): the groups of these {what}s are missing"
            )
        })
        .collect()
}

/// Family number → group indices: a table over the numbers' range when
/// it is small and dense (as MED writers number families), a map
/// otherwise.
enum DenseFamilies {
    Table {
        min: i64,
        groups: Vec<Option<Vec<usize>>>,
    },
    Map(HashMap<i64, Vec<usize>>),
}

impl DenseFamilies {
    fn lookup(&self, num: i64) -> Option<&Vec<usize>> {
        match self {
            DenseFamilies::Table { min, groups } => num
                .checked_sub(*min)
                .and_then(|i| usize::try_from(i).ok())
                .and_then(|i| groups.get(i))
                .and_then(Option::as_ref),
            DenseFamilies::Map(map) => map.get(&num),
        }
    }

    fn get(&self, num: &i64) -> &[usize] {
        self.lookup(*num).map_or(&[], |v| v.as_slice())
    }

    fn defines(&self, num: i64) -> bool {
        self.lookup(num).is_some()
    }
}

fn dense(map: HashMap<i64, Vec<usize>>) -> DenseFamilies {
    let min = map.keys().copied().min().unwrap_or(0);
    let max = map.keys().copied().max().unwrap_or(0);
    let span = max.saturating_sub(min).saturating_add(1);
    if span > 10_000_000 {
        return DenseFamilies::Map(map);
    }
    let mut groups = vec![None; span as usize];
    for (num, ids) in map {
        groups[(num - min) as usize] = Some(ids);
    }
    DenseFamilies::Table { min, groups }
}
