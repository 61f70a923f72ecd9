use crate::catalog::schema::*;
use crate::kws;

pub fn commands() -> Vec<Command> {
    vec![
        Command::new("DEBUT", "Start a study: error handling, debug and publication options.").kw(kws![
            simp("CODE").txt().one_of(&["OUI", "NON"]),
            fact(
                "CODE",
                kws![
                    simp("NIV_PUB_WEB").txt().one_of(&["INTERNET", "INTRANET"]),
                    simp("VISU_EFICAS").txt().one_of(&["OUI", "NON"]),
                ]
            ),
            fact(
                "ERREUR",
                kws![
                    simp("ERREUR_F").txt().one_of(&["ABORT", "EXCEPTION"]),
                    simp("ALARME").txt().one_of(&["ALARME", "EXCEPTION"]),
                ]
            ),
            fact(
                "DEBUG",
                kws![
                    simp("JXVERI").txt().one_of(&["OUI", "NON"]),
                    simp("SDVERI").txt().one_of(&["OUI", "NON"]),
                    simp("JEVEUX").txt().one_of(&["OUI", "NON"]),
                    simp("HIST_ETAPE").txt().one_of(&["OUI", "NON"]),
                    simp("ENVIMA").txt().one_of(&["TEST"]),
                ]
            ),
            simp("IGNORE_ALARM").txt().many(),
            simp("PAR_LOT").txt().one_of(&["OUI", "NON"]),
            simp("LANG").txt(),
            simp("IMPR_MACRO").txt().one_of(&["OUI", "NON"]),
            simp("INFO").i().one_of_i(&[1, 2]),
        ]),
        Command::new("FIN", "End the study; commands after FIN are not run.").kw(kws![
            simp("FORMAT_HDF").txt().one_of(&["OUI", "NON"]),
            simp("RETASSAGE").txt().one_of(&["OUI", "NON"]),
            simp("INFO_RESU").txt().one_of(&["OUI", "NON"]),
            simp("PROC0").txt().one_of(&["OUI", "NON"]),
            simp("UNITE").i(),
        ]),
    ]
}
