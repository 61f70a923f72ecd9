//! Orthotropic conduction (THER_ORTH) in the local frames AFFE_CARA_ELEM MASSIF gives, against closed forms.
//!
//! With the temperature `T = g · x` prescribed on the whole boundary of a box, the linear field is the
//! solution for any constant conductivity tensor `Λ = Σ λᵢ aᵢ aᵢᵀ` (its divergence-free flux), so every
//! point of every cell carries the flux `q = −Λ g` and every cell the energy `ETHE_ELEM = −½ V g · Λ g`.
//! The axes `aᵢ` are computed here on their own: the nautical angles (α, β, γ) as the rotations
//! `R_z(α) R_y(β) R_x(γ)` of the global axes, the Euler angles (ψ, θ, φ) as `R_z(ψ) R_x(θ) R_z(φ)`.

use crate::common::*;

type M3 = [[f64; 3]; 3];

fn mul(a: &M3, b: &M3) -> M3 {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
}

fn rz(t: f64) -> M3 {
    let (s, c) = t.to_radians().sin_cos();
    [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]
}

fn ry(t: f64) -> M3 {
    let (s, c) = t.to_radians().sin_cos();
    [[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]]
}

fn rx(t: f64) -> M3 {
    let (s, c) = t.to_radians().sin_cos();
    [[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]]
}

/// `Λ g` for principal values `lambda` along the columns of the rotation `r`.
fn lambda_g(r: &M3, lambda: [f64; 3], g: [f64; 3], dim: usize) -> [f64; 3] {
    let mut q = [0.0; 3];
    for (k, l) in lambda.iter().enumerate().take(dim) {
        let a: [f64; 3] = std::array::from_fn(|i| r[i][k]);
        let ag: f64 = (0..dim).map(|i| a[i] * g[i]).sum();
        for i in 0..dim {
            q[i] += l * ag * a[i];
        }
    }
    q
}

const LAMBDA: [f64; 3] = [5.0, 1.5, 0.5];

/// The command file: the box on unit 20, `T = g · x` on its boundary `skin`, THER_ORTH in the frame
/// `massif`, the flux components and the cells' energy tested against `q` and `e`.
fn comm(modelisation: &str, skin: &str, massif: &str, g: [f64; 3], q: [f64; 3], e: f64, dim: usize) -> String {
    let cmps = ["FLUX", "FLUY", "FLUZ"];
    let mut tests = String::new();
    for (k, c) in cmps.iter().enumerate().take(dim) {
        for tt in ["MIN", "MAX"] {
            tests += &format!(
                "    _F(RESULTAT=RES, INST=0.0, NOM_CHAM=\"FLUX_ELGA\", NOM_CMP=\"{c}\", TYPE_TEST=\"{tt}\", \
                 VALE_CALC={v:e}, VALE_REFE={v:e}, REFERENCE=\"ANALYTIQUE\", PRECISION=1e-9, CRITERE=\"ABSOLU\"),\n",
                v = -q[k]
            );
        }
    }
    for tt in ["MIN", "MAX"] {
        tests += &format!(
            "    _F(RESULTAT=RES, INST=0.0, NOM_CHAM=\"ETHE_ELEM\", NOM_CMP=\"TOTALE\", TYPE_TEST=\"{tt}\", \
             VALE_CALC={e:e}, VALE_REFE={e:e}, REFERENCE=\"ANALYTIQUE\", PRECISION=1e-9),\n"
        );
    }
    format!(
        r#"DEBUT(CODE="OUI")
MA = LIRE_MAILLAGE(FORMAT="MED", UNITE=20)
MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT="OUI", PHENOMENE="THERMIQUE", MODELISATION="{modelisation}"))
MAT = DEFI_MATERIAU(THER_ORTH=_F(LAMBDA_L={l0}, LAMBDA_T={l1}, LAMBDA_N={l2}, RHO_CP=1.0))
CM = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT="OUI", MATER=MAT))
CAR = AFFE_CARA_ELEM(MODELE=MO, MASSIF=_F(GROUP_MA={cells}, {massif}))
TG = FORMULE(VALE="{g0}*X + {g1}*Y + {g2}*Z", NOM_PARA=("X", "Y", "Z"))
CH = AFFE_CHAR_THER_F(MODELE=MO, TEMP_IMPO=_F(GROUP_NO={skin}, TEMP=TG))
RES = THER_LINEAIRE(MODELE=MO, CHAM_MATER=CM, CARA_ELEM=CAR, EXCIT=_F(CHARGE=CH), TYPE_CALCUL="STAT",
                    INCREMENT=_F(LIST_INST=DEFI_LIST_REEL(VALE=0.0)))
RES = CALC_CHAMP(reuse=RES, RESULTAT=RES, THERMIQUE=("FLUX_ELGA", "ETHE_ELEM"))
TEST_RESU(RESU=(
{tests}))
FIN()
"#,
        l0 = LAMBDA[0],
        l1 = LAMBDA[1],
        l2 = LAMBDA[2],
        g0 = g[0],
        g1 = g[1],
        g2 = g[2],
        cells = if dim == 3 { "\"VOLUME\"" } else { "\"SURFACE\"" },
    )
}

fn check(tag: &str, mesh: (&str, &str, &str), comm: &str, checks: usize) {
    let dir = scratch!(tag);
    std::fs::create_dir_all(&dir).unwrap();
    let (status, mess, _) = run_on_box(&dir, mesh, comm);
    assert!(status.success(), "{mess}");
    let ok = mess.lines().filter(|l| l.trim_start().starts_with("OK  ANALYTIQUE")).count();
    assert_eq!(ok, checks, "{mess}");
    assert!(!mess.lines().any(|l| l.trim_start().starts_with("NOOK")), "{mess}");
    let _ = std::fs::remove_dir_all(&dir);
}

const G: [f64; 3] = [1.0, 2.0, -3.0];

#[test]
fn nautical_angles_turn_the_conductivity_in_3d() {
    let (a, b, c) = (30.0, 20.0, 10.0);
    let r = mul(&mul(&rz(a), &ry(b)), &rx(c));
    let q = lambda_g(&r, LAMBDA, G, 3);
    let e = -0.5 * 0.125 * (0..3).map(|i| G[i] * q[i]).sum::<f64>();
    let skin = r#"("XMIN", "XMAX", "YMIN", "YMAX", "ZMIN", "ZMAX")"#;
    let text = comm("3D", skin, &format!("ANGL_REP=({a}, {b}, {c})"), G, q, e, 3);
    check("nautical", ("HEXA8", "2,2,2", "1,1,1"), &text, 8);
}

#[test]
fn euler_angles_turn_the_conductivity_in_3d() {
    let (psi, theta, phi) = (25.0, 40.0, -35.0);
    let r = mul(&mul(&rz(psi), &rx(theta)), &rz(phi));
    let q = lambda_g(&r, LAMBDA, G, 3);
    // Six tetrahedra per cube of volume 1/8.
    let e = -0.5 * 0.125 / 6.0 * (0..3).map(|i| G[i] * q[i]).sum::<f64>();
    let skin = r#"("XMIN", "XMAX", "YMIN", "YMAX", "ZMIN", "ZMAX")"#;
    let text = comm("3D", skin, &format!("ANGL_EULER=({psi}, {theta}, {phi})"), G, q, e, 3);
    check("euler", ("TETRA4", "2,2,2", "1,1,1"), &text, 8);
}

#[test]
fn a_plane_frame_turns_by_its_first_angle_only() {
    // In the plane β and γ are ignored, as Code_Aster does.
    let g = [G[0], G[1], 0.0];
    let q = lambda_g(&rz(-40.0), LAMBDA, g, 2);
    let e = -0.5 * 0.25 * (0..2).map(|i| g[i] * q[i]).sum::<f64>();
    let skin = r#"("BAS", "DROITE", "HAUT", "GAUCHE")"#;
    let text = comm("PLAN", skin, "ANGL_REP=(-40.0, 15.0, 5.0)", g, q, e, 2);
    check("plane", ("QUAD8", "2,2", "1,1"), &text, 6);
}

#[test]
fn orthotropic_materials_need_their_frame_and_structural_keywords_stop_by_name() {
    let dir = scratch!("refuse");
    std::fs::create_dir_all(&dir).unwrap();
    let skin = r#"("BAS", "DROITE", "HAUT", "GAUCHE")"#;
    let base = comm("PLAN", skin, "ANGL_REP=0.0", [1.0, 0.0, 0.0], [-5.0, 0.0, 0.0], -1.25, 2);
    let cases = [
        (base.replace("CARA_ELEM=CAR, ", ""), "THER_ORTH needs the local axes"),
        (
            base.replace(
                "MASSIF=_F(GROUP_MA=\"SURFACE\", ANGL_REP=0.0)",
                "POUTRE=_F(GROUP_MA=\"SURFACE\", SECTION=\"CERCLE\", CARA=\"R\", VALE=0.1)",
            ),
            "POUTRE",
        ),
    ];
    for (text, needle) in cases {
        let (status, mess, _) = run_on_box(&dir, ("QUAD4", "2,2", "1,1"), &text);
        assert!(!status.success(), "{mess}");
        let fatal = mess.lines().find(|l| l.contains("<F>")).unwrap_or_default();
        assert!(fatal.contains(needle), "{fatal}\n{mess}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
