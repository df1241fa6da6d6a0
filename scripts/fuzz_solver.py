"""Random non-default solver options for the scenes of scripts/fuzz-scenes.py (--solver-options).

A user runs experiments from options files: another K+ representation or precision, another coarse solver,
another preconditioner in face, no bonded start, friction polygons, the outer loop's penalty and tolerances, the
inner solver's expansions and step lengths. Each choice is valid on its own and in any combination, so a run with
them must still end converged within the acceptance or say why not, like a run with the defaults; what it may
change is the count of products and whether the solver reaches the acceptance within its limits. A combination
the program refuses must be refused by an error that names one of the drawn options (class OK-refused of
fuzz-scenes.py), never by a crash.

The options of scene i of seed S depend only on (S, i) and are drawn from their own random stream, so that
--solver-options leaves the scene itself (its bodies, loads, laws, ranks) as it is without the flag.
"""

import random

# (option, values, needs friction): values that differ from the option's default, or from the default some scenes get
# (-contact_pc_type's default follows the K+ blocks, the expansions' the preconditioner). The inner solver's options
# are written for mpgp (disks) and renamed for mprgp where that is the inner solver (no friction, or polygons); the
# merged Coulomb algorithm names its inner solvers by block and ignores them, as -fem_dirichlet_min_hold is ignored
# with -fem_dirichlet multipliers
OPTIONS = [
    ("-feti_kplus", ["implicit", "explicit"], False),
    ("-feti_kplus_precision", ["double"], False),
    ("-feti_kplus_refine", ["1"], False),
    ("-feti_kplus_explicit_schur", ["0"], False),
    ("-feti_kplus_memory_budget", ["0.001"], False),
    ("-feti_dirichlet_pc_precision", ["double"], False),
    ("-feti_coarse_mode", ["single", "redundant", "parallel", "split"], False),
    ("-feti_rigid_rows", ["0"], False),
    ("-feti_fixing_nodes", ["4", "16"], False),
    ("-fem_matrix_type", ["aij"], False),
    ("-fem_balance_multipliers", ["0"], False),
    ("-fem_dirichlet_min_hold", ["0", "0.9"], False),
    ("-contact_pc_type", ["none", "lumped", "dirichlet"], False),
    ("-contact_pc_contact_rows_scaled", ["0"], False),
    ("-contact_pc_inner_projector", ["1"], False),
    ("-contact_start_rtol", ["0", "0.01", "0.5"], False),
    ("-contact_start_compressive", ["0", "1"], False),
    ("-contact_friction_polygon", ["2", "4", "8"], True),
    ("-contact_coulomb_follow_radii", ["0"], True),
    ("-contact_fixed_point_rtol", ["1e-3", "1e-8"], True),
    ("-contact_msa_recycle", ["0"], True),
    ("-contact_msa_start_rtol", ["0.1", "1e-4"], True),
    ("-contact_kkt_check", ["1"], False),
    ("-contact_refine_max", ["0", "1"], False),
    ("-contact_tao_smalxe_rho", ["0.3", "3", "10"], False),
    ("-contact_tao_smalxe_rho_first", ["0.5", "2"], False),
    ("-contact_tao_smalxe_M", ["0.01", "1"], False),
    ("-contact_tao_smalxe_M_min", ["1e-6", "0.05"], False),
    ("-contact_tao_smalxe_eta", ["1", "0.01"], False),
    ("-contact_tao_smalxe_beta", ["2", "100"], False),
    ("-contact_tao_smalxe_update", ["rho", "none"], False),
    ("-contact_tao_smalxe_anderson", ["0", "2", "3"], False),
    ("-contact_tao_smalxe_anderson_start", ["1", "5"], False),
    ("-contact_tao_smalxe_penalty_pc", ["0"], False),
    ("-contact_tao_smalxe_pc_q_scale", ["0.5", "2"], False),
    ("-contact_tao_smalxe_inner_floor", ["0", "1"], False),
    ("-contact_tao_smalxe_norm_method", ["power"], False),
    ("-contact_tao_smalxe_subsolver_tao_mpgp_alpha", ["1", "2"], False),
    ("-contact_tao_smalxe_subsolver_tao_mpgp_gamma", ["0.3", "3"], False),
    ("-contact_tao_smalxe_subsolver_tao_mpgp_bb", ["1"], False),
    ("-contact_tao_smalxe_subsolver_tao_mpgp_arc", ["0"], True),
    ("-contact_tao_smalxe_subsolver_tao_mpgp_expansion_projcg", ["0", "1"], False),
    ("-contact_tao_smalxe_subsolver_tao_mpgp_expansion_lagged", ["0", "1"], False),
    ("-contact_tao_smalxe_subsolver_tao_mpgp_expansion_lookahead", ["2"], False),
    ("-contact_tao_smalxe_subsolver_tao_mpgp_expansion_gradient", ["1"], False),
    ("-contact_tao_smalxe_subsolver_tao_mpgp_norm_method", ["power"], False),
]


def draw(seed, index, friction):
    """1 to 4 options with their values for scene index of seed, as a list of command-line words."""
    rng = random.Random(f"conefeti-fuzz-solver:{seed}:{index}")
    candidates = [o for o in OPTIONS if friction or not o[2]]
    chosen = rng.sample(candidates, rng.randint(1, 4))
    inner = "mpgp" if friction and not any(name == "-contact_friction_polygon" for name, _, _ in chosen) else "mprgp"
    words = []
    for name, values, _ in chosen:
        words += [name.replace("_tao_mpgp_", f"_tao_{inner}_"), rng.choice(values)]
    return words
