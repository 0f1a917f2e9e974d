"""Writes the small HDF5 files the reader tests use (run with h5py; the
outputs are committed so the tests need nothing but the repository).

- chunked_v3.h5: libver earliest: chunked datasets (v1 B-tree index) with
  deflate and shuffle, a compact dataset, big-endian integers, 16 links in
  an old-style group.
- latest.h5: libver latest: superblock v3, object header v2, 20 links in a
  new-style group (dense storage), 12 attributes (dense), a single-chunk
  deflated dataset, an implicit-index dataset, a fixed-array-indexed one.
"""
import h5py, numpy as np

with h5py.File("chunked_v3.h5", "w", libver="earliest") as f:
    g = f.create_group("G")
    for i in range(16):
        g.create_group(f"child{i:02d}")
    a = np.arange(1000, dtype="<f8") * 0.5
    f.create_dataset("deflate", data=a, chunks=(64,), compression="gzip", shuffle=True)
    b = np.arange(30, dtype="<i4").reshape(5, 6)
    f.create_dataset("chunked2d", data=b, chunks=(2, 4))
    dcpl = h5py.h5p.create(h5py.h5p.DATASET_CREATE)
    dcpl.set_layout(h5py.h5d.COMPACT)
    sp = h5py.h5s.create_simple((4,))
    d = h5py.h5d.create(f.id, b"compact", h5py.h5t.STD_I16LE, sp, dcpl=dcpl)
    d.write(h5py.h5s.ALL, h5py.h5s.ALL, np.array([1, -2, 3, -4], dtype="<i2"))
    f.create_dataset("bigendian", data=np.array([1, 2, 70000], dtype=">i8"))
    f["deflate"].attrs["NBR"] = np.int32(1000)

with h5py.File("latest.h5", "w", libver="latest") as f:
    g = f.create_group("MANY")
    for i in range(20):
        g.create_group(f"g{i:02d}")
    for i in range(12):
        g.attrs[f"A{i:02d}"] = np.int64(i * 10)
    g.attrs["TEXT"] = np.bytes_(b"hello")
    a = np.linspace(0.0, 1.0, 50)
    f.create_dataset("single", data=a, chunks=(50,), compression="gzip")
    dcpl = h5py.h5p.create(h5py.h5p.DATASET_CREATE)
    dcpl.set_chunk((4,))
    dcpl.set_alloc_time(h5py.h5d.ALLOC_TIME_EARLY)
    sp = h5py.h5s.create_simple((10,))
    d = h5py.h5d.create(f.id, b"implicit", h5py.h5t.STD_I32LE, sp, dcpl=dcpl)
    d.write(h5py.h5s.ALL, h5py.h5s.ALL, np.arange(10, dtype="<i4") * 3)
    f.create_dataset("fixed_array", data=np.arange(40, dtype="<i4"), chunks=(8,))
