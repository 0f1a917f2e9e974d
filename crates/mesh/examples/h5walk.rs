//! Print every object of an HDF5 file with its attributes and shape:
//! a debugging aid for the HDF5 reader.

use aster_mesh::hdf5::{H5File, Object};

fn walk(f: &H5File, o: &Object, path: &str, depth: usize) {
    if depth > 20 {
        return;
    }
    let attrs = match f.attributes(o) {
        Ok(a) => a
            .iter()
            .map(|a| {
                format!(
                    "{}={:?}",
                    a.name,
                    a.as_i64().map(|v| v.to_string()).or(a.as_string())
                )
            })
            .collect::<Vec<_>>()
            .join(" "),
        Err(e) => format!("ATTR ERROR {e}"),
    };
    if o.is_dataset() {
        match f.read(o) {
            Ok(d) => println!("{path} {:?} {:?} {attrs}", d.dims, d.datatype),
            Err(e) => println!("{path} READ ERROR {e}"),
        }
        return;
    }
    println!("{path}/ {attrs}");
    match f.links(o) {
        Ok(links) => {
            for (name, addr) in links {
                match f.object_at(addr) {
                    Ok(c) => walk(f, &c, &format!("{path}/{name}"), depth + 1),
                    Err(e) => println!("{path}/{name} OBJECT ERROR {e} (addr {addr})"),
                }
            }
        }
        Err(e) => println!("{path} LINKS ERROR {e}"),
    }
}

fn main() {
    for arg in std::env::args().skip(1) {
        let data = std::fs::read(&arg).unwrap_or_default();
        match H5File::from_bytes(data) {
            Ok(f) => match f.root() {
                Ok(r) => walk(&f, &r, "", 0),
                Err(e) => println!("{arg}: ROOT ERROR {e}"),
            },
            Err(e) => println!("{arg}: {e}"),
        }
    }
}
