//! AFFE_MODELE: the physical phenomenon and finite-element type of each part of a mesh.

use crate::catalog::schema::*;
use crate::concepts::ConceptKind;
use crate::kws;

pub fn commands() -> Vec<Command> {
    vec![affe_modele()]
}

/// Mechanical modelisations.
const MODELISATIONS_MECA: &[&str] = &[
    "2D_DIS_T",
    "2D_DIS_TR",
    "2D_FLUI_ABSO",
    "2D_FLUI_PESA",
    "2D_FLUI_STRU",
    "2D_FLUIDE",
    "3D",
    "3D_ABSO",
    "3D_FAISCEAU",
    "3D_FLUI_ABSO",
    "3D_FLUIDE",
    "3D_INCO_UPG",
    "3D_INCO_UP",
    "3D_INCO_UPO",
    "3D_MIX_STA",
    "3D_SI",
    "3D_GRAD_VARI",
    "3D_GRAD_INCO",
    "3D_JOINT",
    "3D_JOINT_HYME",
    "3D_INTERFACE",
    "3D_INTERFACE_S",
    "3D_INTERF_POU",
    "AXIS",
    "AXIS_FLUI_STRU",
    "AXIS_FLUI_ABSO",
    "AXIS_FLUIDE",
    "AXIS_FOURIER",
    "AXIS_INCO_UPG",
    "AXIS_INCO_UP",
    "AXIS_INCO_UPO",
    "AXIS_SI",
    "AXIS_GRAD_VARI",
    "AXIS_GRAD_INCO",
    "AXIS_JOINT",
    "AXIS_INTERFACE",
    "AXIS_INTERFACE_S",
    "BARRE",
    "CABLE_GAINE",
    "2D_BARRE",
    "C_PLAN",
    "C_PLAN_SI",
    "CABLE",
    "CABLE_POULIE",
    "COQUE_3D",
    "COQUE_AXIS",
    "D_PLAN",
    "D_PLAN_GRAD_VARI",
    "D_PLAN_GRAD_INCO",
    "D_PLAN_GRAD_SIGM",
    "PLAN_JOINT",
    "PLAN_JOINT_HYME",
    "PLAN_INTERFACE",
    "PLAN_INTERFACE_S",
    "D_PLAN_ABSO",
    "D_PLAN_INCO_UPG",
    "D_PLAN_INCO_UP",
    "D_PLAN_INCO_UPO",
    "D_PLAN_SI",
    "D_PLAN_MIX_STA",
    "DIS_T",
    "DIS_TR",
    "DKT",
    "DKTG",
    "DST",
    "FLUI_STRU",
    "POU_FLUI_STRU",
    "GRILLE_EXCENTRE",
    "GRILLE_MEMBRANE",
    "MEMBRANE",
    "POU_D_E",
    "POU_D_EM",
    "POU_D_T",
    "POU_D_T_GD",
    "POU_D_TG",
    "POU_D_TGM",
    "POU_D_SQUE",
    "Q4G",
    "Q4GG",
    "TUYAU_3M",
    "TUYAU_6M",
    "COQUE_SOLIDE",
    "D_PLAN_HHM",
    "D_PLAN_HH2M_SI",
    "D_PLAN_HM",
    "D_PLAN_HM_SI",
    "D_PLAN_HM_SI_DIL",
    "D_PLAN_THM",
    "D_PLAN_HHMD",
    "D_PLAN_HH2MD",
    "D_PLAN_HMD",
    "D_PLAN_THHD",
    "D_PLAN_THH2D",
    "D_PLAN_THVD",
    "D_PLAN_THH2MD",
    "D_PLAN_THHMD",
    "D_PLAN_THMD",
    "D_PLAN_HHMS",
    "D_PLAN_HH2MS",
    "D_PLAN_HH2MS_DIL",
    "D_PLAN_HMS",
    "D_PLAN_HMS_DIL",
    "D_PLAN_THHS",
    "D_PLAN_THH2S",
    "D_PLAN_THVS",
    "D_PLAN_THH2MS",
    "D_PLAN_THHMS",
    "D_PLAN_THMS",
    "D_PLAN_THMS_DIL",
    "D_PLAN_HS",
    "D_PLAN_HHD",
    "D_PLAN_HHS",
    "D_PLAN_HH2D",
    "D_PLAN_HH2S",
    "D_PLAN_2DG",
    "D_PLAN_DIL",
    "3D_DIL",
    "AXIS_THM",
    "AXIS_HHM",
    "AXIS_HM",
    "AXIS_HH2MD",
    "AXIS_HHMD",
    "AXIS_HMD",
    "AXIS_THHD",
    "AXIS_THH2D",
    "AXIS_THVD",
    "AXIS_THHMD",
    "AXIS_THH2MD",
    "AXIS_THMD",
    "AXIS_HH2MS",
    "AXIS_HHMS",
    "AXIS_HMS",
    "AXIS_THHS",
    "AXIS_THH2S",
    "AXIS_THVS",
    "AXIS_THHMS",
    "AXIS_THH2MS",
    "AXIS_THMS",
    "AXIS_HHD",
    "AXIS_HHS",
    "AXIS_HH2D",
    "AXIS_HH2S",
    "3D_HHM",
    "3D_HH2M_SI",
    "3D_HM",
    "3D_HM_SI",
    "3D_HM_SI_DIL",
    "3D_THHM",
    "3D_THM",
    "3D_HHMD",
    "3D_HMD",
    "3D_THHD",
    "3D_THVD",
    "3D_THHMD",
    "3D_THMD",
    "3D_HHMS",
    "3D_HMS",
    "3D_HMS_DIL",
    "3D_THHS",
    "3D_THVS",
    "3D_THHMS",
    "3D_THMS",
    "3D_THMS_DIL",
    "3D_THH2MD",
    "3D_THH2MS",
    "3D_HH2MD",
    "3D_HH2MS",
    "3D_HH2MS_DIL",
    "3D_THH2S",
    "3D_THH2D",
    "3D_HS",
    "3D_HHD",
    "3D_HHS",
    "3D_HH2D",
    "3D_HH2S",
    "3D_HH2SUDA",
    "D_PLAN_HH2SUDA",
    "PLAN_JHMS",
    "AXIS_JHMS",
    "3D_HHO",
    "D_PLAN_HHO",
    "AXIS_HHO",
    "3D_GRAD_HHO",
    "D_PLAN_GRAD_HHO",
    "AXIS_GRAD_HHO",
    "PLAQ_MITC",
];

/// Thermal modelisations.
const MODELISATIONS_THER: &[&str] = &[
    "3D",
    "3D_DIAG",
    "AXIS",
    "AXIS_DIAG",
    "AXIS_FOURIER",
    "COQUE",
    "COQUE_AXIS",
    "COQUE_PLAN",
    "PLAN",
    "PLAN_DIAG",
    "3D_HHO",
    "PLAN_HHO",
    "AXIS_HHO",
    "AXIS_SECH",
    "3D_SECH",
    "AXIS_SECH_DIAG",
    "3D_SECH_DIAG",
];

fn formulation(modelisations: &'static [&'static str], values: &'static [&'static str], default: &'static str) -> Bloc {
    bloc(is_in("MODELISATION", modelisations), kws![simp("FORMULATION").txt().d(default).one_of(values)])
}

fn affe_modele() -> Command {
    Command::new("AFFE_MODELE", "Assign a phenomenon and a finite-element modelisation to the cells of a mesh.")
        .produces(ConceptKind::Modele)
        .kw(kws![
            simp("MAILLAGE").co(&[ConceptKind::Maillage]).o(),
            simp("INFO").i().d(1).one_of_i(&[1, 2]),
            fact(
                "GRANDEUR_CARA",
                kws![
                    simp("LONGUEUR").r().val_min(0.0),
                    simp("PRESSION").r().val_min(0.0),
                    simp("TEMPERATURE").r().val_min(0.0),
                ]
            ),
            fact(
                "AFFE_SOUS_STRUC",
                kws![
                    simp("TOUT").txt().one_of(&["OUI"]),
                    simp("SUPER_MAILLE").txt().many(),
                    simp("PHENOMENE").txt().d("MECANIQUE").one_of(&["MECANIQUE"]),
                ]
            )
            .rules(vec![un_parmi(&["TOUT", "SUPER_MAILLE"])]),
            fact(
                "AFFE",
                kws![
                    simp("TOUT").txt().one_of(&["OUI"]),
                    simp("GROUP_MA").txt().many(),
                    simp("PHENOMENE").txt().o().one_of(&["MECANIQUE", "THERMIQUE", "ACOUSTIQUE"]),
                    bloc(
                        eq("PHENOMENE", "MECANIQUE"),
                        kws![
                            simp("MODELISATION").txt().o().one_of(MODELISATIONS_MECA),
                            formulation(
                                &["3D_HHO", "D_PLAN_HHO", "AXIS_HHO"],
                                &["LINEAIRE", "QUADRATIQUE", "CUBIQUE", "QUARTIQUE"],
                                "LINEAIRE"
                            ),
                            formulation(
                                &["D_PLAN_GRAD_HHO", "3D_GRAD_HHO", "AXIS_GRAD_HHO"],
                                &["LINEAIRE", "QUADRATIQUE"],
                                "LINEAIRE"
                            ),
                            formulation(
                                &[
                                    "2D_FLUIDE",
                                    "2D_FLUI_ABSO",
                                    "2D_FLUI_PESA",
                                    "2D_FLUI_STRU",
                                    "3D_FLUIDE",
                                    "3D_FLUI_ABSO",
                                    "AXIS_FLUIDE",
                                    "AXIS_FLUI_STRU",
                                    "AXIS_FLUI_ABSO",
                                    "FLUI_STRU",
                                ],
                                &["U_P_PHI", "U_P", "U_PSI"],
                                "U_P_PHI"
                            ),
                            formulation(&["D_PLAN_DIL", "3D_DIL"], &["DIL", "DIL_INCO"], "DIL"),
                            formulation(&["D_PLAN_MIX_STA", "3D_MIX_STA"], &["STA", "STA_INCO"], "STA"),
                        ]
                    ),
                    bloc(
                        eq("PHENOMENE", "THERMIQUE"),
                        kws![
                            simp("MODELISATION").txt().o().one_of(MODELISATIONS_THER),
                            formulation(
                                &["3D_HHO", "PLAN_HHO", "AXIS_HHO"],
                                &["CONSTANTE", "LINEAIRE", "QUADRATIQUE", "CUBIQUE", "QUARTIQUE"],
                                "LINEAIRE"
                            ),
                        ]
                    ),
                    bloc(
                        eq("PHENOMENE", "ACOUSTIQUE"),
                        kws![simp("MODELISATION").txt().o().one_of(&["3D", "PLAN", "3D_ABSO", "PLAN_ABSO"])]
                    ),
                ]
            )
            .many()
            .rules(vec![un_parmi(&["TOUT", "GROUP_MA"])]),
            fact(
                "DISTRIBUTION",
                kws![
                    simp("METHODE").txt().d("SOUS_DOMAINE").one_of(&[
                        "MAIL_CONTIGU",
                        "MAIL_DISPERSE",
                        "CENTRALISE",
                        "GROUP_ELEM",
                        "SOUS_DOMAINE",
                    ]),
                    bloc(
                        is_in("METHODE", &["MAIL_DISPERSE", "MAIL_CONTIGU"]),
                        kws![simp("CHARGE_PROC0_MA").i().d(100).val_min(0.0).val_max(100.0)]
                    ),
                    bloc(
                        eq("METHODE", "SOUS_DOMAINE"),
                        kws![
                            simp("NB_SOUS_DOMAINE").i(),
                            simp("PARTITIONNEUR").txt().d("METIS").one_of(&["METIS", "SCOTCH"]),
                        ]
                    ),
                ]
            )
            .d(),
            simp("VERI_JACOBIEN").txt().d("OUI").one_of(&["OUI", "NON"]),
            simp("VERI_NORM_IFS").txt().d("OUI").one_of(&["OUI", "NON"]),
            simp("VERI_FORMULATION_IFS").txt().d("OUI").one_of(&["OUI", "NON"]),
            simp("VERI_PLAN").txt().d("OUI").one_of(&["OUI", "NON"]),
        ])
        .rules(vec![au_moins_un(&["AFFE", "AFFE_SOUS_STRUC"])])
}
