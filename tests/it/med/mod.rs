//! Meshes and results on disk: MED round trips (meshes, node fields, cell fields with LIRE_RESU), the
//! reference MED tools and meshio, every mesh of the corpus against an independent reader, the mesh
//! stages (LIRE_MAILLAGE, DEFI_GROUP, CREA_MAILLAGE, `aster mesh`), and the printed formats (RESULTAT,
//! GMSH, tables).
mod cell_fields;
mod corpus_meshes;
mod crea_maillage;
mod mesh_stages;
mod print_formats;
mod roundtrip;
mod tools;
