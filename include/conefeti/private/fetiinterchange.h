/* Private: the contact pairing of the FETI interchange file (format version 2, docs/feti-interchange.md),
   shared by the feti layer, which owns the file (src/feti/fetiio.cxx), and the contact layer, which knows
   what a law is (src/contact/contactio.cxx: FETIWriteContact(), FETILoadContact()). */
#pragma once

#include <conefeti/feti.h>

#include <vector>

/* Per contact node: its normal row of B, its two tangential rows (-1 when it has none), its law as the
   contact layer numbers it (ContactLaw: 0 frictionless, 1 Tresca, 2 Coulomb) and its coefficient (Tresca:
   slip bound, Coulomb: friction coefficient, frictionless: 0). Global row indices. The feti layer stores
   the law without interpreting it beyond the number of tangential rows it implies. */
struct FETIContactPairing {
  std::vector<PetscInt>  normal, t1, t2, law;
  std::vector<PetscReal> coef;
};

/* pairing: the contact nodes of this rank (any rank may hold any node), or NULL: the file then says that it
   carries no pairing, which a contact reader rejects if the problem has contact rows */
PETSC_INTERN PetscErrorCode FETIWriteWithPairing_Private(FETI, PetscViewer, const FETIContactPairing *);
/* pairing: every node of the file on every rank; *given: whether the file carries a pairing (version 2
   written with one); the rows of B are spread so that no contact node's rows straddle two ranks */
PETSC_INTERN PetscErrorCode FETILoadWithPairing_Private(FETI, PetscViewer, FETIContactPairing *, PetscBool *);
