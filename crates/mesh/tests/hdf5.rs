//! The HDF5 reader on small files made with the HDF5 C library (through
//! h5py, by `tests/data/make_hdf5_fixtures.py`): layouts and storage MED
//! files may use beyond what our own writer produces.

use aster_mesh::hdf5::{Datatype, H5File};
use std::path::Path;

fn open(name: &str) -> H5File {
    let p = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name);
    H5File::from_bytes(std::fs::read(p).unwrap()).unwrap()
}

fn f64s(f: &H5File, path: &str) -> Vec<f64> {
    let o = f.get(path).unwrap().unwrap();
    f.read(&o).unwrap().to_f64().unwrap()
}

fn i64s(f: &H5File, path: &str) -> Vec<i64> {
    let o = f.get(path).unwrap().unwrap();
    f.read(&o).unwrap().to_i64().unwrap()
}

#[test]
fn chunked_deflate_shuffle_with_v1_btree() {
    let f = open("chunked_v3.h5");
    let v = f64s(&f, "deflate");
    assert_eq!(v.len(), 1000);
    assert!(v.iter().enumerate().all(|(i, &x)| x == i as f64 * 0.5));
    let o = f.get("deflate").unwrap().unwrap();
    assert_eq!(
        f.attribute(&o, "NBR").unwrap().unwrap().as_i64(),
        Some(1000)
    );
}

#[test]
fn partial_edge_chunks_in_two_dimensions() {
    let f = open("chunked_v3.h5");
    let o = f.get("chunked2d").unwrap().unwrap();
    let d = f.read(&o).unwrap();
    assert_eq!(d.dims, [5, 6]);
    assert_eq!(d.to_i64().unwrap(), (0..30).collect::<Vec<i64>>());
}

#[test]
fn compact_and_big_endian_data() {
    let f = open("chunked_v3.h5");
    assert_eq!(i64s(&f, "compact"), [1, -2, 3, -4]);
    let o = f.get("bigendian").unwrap().unwrap();
    let d = f.read(&o).unwrap();
    assert_eq!(
        d.datatype,
        Datatype::Int {
            size: 8,
            signed: true,
            big_endian: true
        }
    );
    assert_eq!(d.to_i64().unwrap(), [1, 2, 70000]);
}

#[test]
fn old_style_group_with_several_symbol_nodes() {
    let f = open("chunked_v3.h5");
    let g = f.get("G").unwrap().unwrap();
    let names: Vec<String> = f.links(&g).unwrap().into_iter().map(|l| l.0).collect();
    assert_eq!(
        names,
        (0..16).map(|i| format!("child{i:02}")).collect::<Vec<_>>()
    );
}

#[test]
fn latest_format_dense_links_and_attributes() {
    let f = open("latest.h5");
    let g = f.get("MANY").unwrap().unwrap();
    let names: Vec<String> = f.links(&g).unwrap().into_iter().map(|l| l.0).collect();
    assert_eq!(
        names,
        (0..20).map(|i| format!("g{i:02}")).collect::<Vec<_>>()
    );
    let attrs = f.attributes(&g).unwrap();
    assert_eq!(attrs.len(), 13);
    assert_eq!(f.attribute(&g, "A07").unwrap().unwrap().as_i64(), Some(70));
    assert_eq!(
        f.attribute(&g, "TEXT")
            .unwrap()
            .unwrap()
            .as_string()
            .unwrap(),
        "hello"
    );
}

#[test]
fn latest_format_chunk_indexes() {
    let f = open("latest.h5");
    let single = f64s(&f, "single");
    assert_eq!(single.len(), 50);
    assert!((single[49] - 1.0).abs() < 1e-15 && (single[1] - 1.0 / 49.0).abs() < 1e-15);
    assert_eq!(
        i64s(&f, "implicit"),
        (0..10).map(|i| 3 * i).collect::<Vec<i64>>()
    );
    assert_eq!(i64s(&f, "fixed_array"), (0..40).collect::<Vec<i64>>());
}
