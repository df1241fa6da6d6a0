/* The contact pairing in the FETI interchange file: which rows of B form one contact node (normal row,
   two tangential rows), with its law and coefficient, written from and read into a ContactProblem. The
   feti layer owns the file (src/feti/fetiio.cxx, format version 2, docs/feti-interchange.md); this file
   turns the contact problem's nodes into the format's pairing and back, since only this layer knows what
   a ContactLaw is. */
#include <conefeti/private/contactimpl.h>
#include <conefeti/private/fetiinterchange.h>

/*@C
  FETIWriteContact - Write a FETI problem with the contact pairing of a contact problem on it: for every contact
  node its normal row of B, its two tangential rows (-1 for a frictionless node), its law and its coefficient.

  Collective

  Input Parameters:
+ feti   - the FETI problem, set up
. cp     - the contact problem whose multipliers are the rows of feti's B (its nodes as given to `ContactProblemAddNodes()`)
- viewer - a binary viewer (`PetscViewerBinaryOpen()`)

  Notes:
  The file is the one of `FETIWrite()` (docs/feti-interchange.md, version 2) with the pairing filled in, so
  `FETILoad()` reads it too; `FETILoadContact()` reads the problem and the pairing back. The pairing makes the
  file self-contained for a contact solve: another code can find the friction cones without relying on the
  order of the rows. Friction polygons (`ContactProblemAddPolygonNodes()`) are not part of the format.

  Example:
.vb
  PetscViewerBinaryOpen(PETSC_COMM_WORLD, "contact.feti", FILE_MODE_WRITE, &viewer);
  FETIWriteContact(feti, cp, viewer);
  PetscViewerDestroy(&viewer);
.ve

  Level: intermediate

.seealso: `FETILoadContact()`, `FETIWrite()`, `ContactProblemAddNodes()`
@*/
PetscErrorCode FETIWriteContact(FETI feti, ContactProblem cp, PetscViewer viewer)
{
  FETIContactPairing pairing;
  PetscInt           n, polygon;
  const PetscInt    *normal, *t1, *t2;
  const ContactLaw  *law;
  const PetscReal   *coef;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(feti, FETI_CLASSID, 1);
  PetscValidHeaderSpecific(cp, CONTACTPROBLEM_CLASSID, 2);
  PetscValidHeaderSpecific(viewer, PETSC_VIEWER_CLASSID, 3);
  PetscCall(ContactProblemGetFrictionPolygon(cp, &polygon, NULL));
  PetscCheck(!polygon, PetscObjectComm((PetscObject)cp), PETSC_ERR_SUP,
             "FETIWriteContact(): the contact problem has friction polygons of %" PetscInt_FMT " directions; the interchange format stores friction disks only", polygon);
  PetscCall(ContactProblemGetNodes(cp, &n, &normal, &t1, &t2, &law, &coef));
  for (PetscInt k = 0; k < n; k++) {
    PetscCallCXX(pairing.normal.push_back(normal[k]));
    PetscCallCXX(pairing.t1.push_back(t1[k]));
    PetscCallCXX(pairing.t2.push_back(t2[k]));
    PetscCallCXX(pairing.law.push_back((PetscInt)law[k]));
    PetscCallCXX(pairing.coef.push_back(coef[k]));
  }
  PetscCall(FETIWriteWithPairing_Private(feti, viewer, &pairing));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FETILoadContact - Read a FETI problem and its contact pairing: the FETI object gets the problem (as `FETILoad()`),
  the contact problem the contact nodes (as `ContactProblemAddNodes()`).

  Collective

  Input Parameters:
+ feti   - a FETI object from `FETICreate()`, empty
. cp     - a contact problem from `ContactProblemCreate()`, not yet set up
- viewer - a binary viewer (`PetscViewerBinaryOpen()` with `FILE_MODE_READ`)

  Notes:
  The rows of B are spread over the ranks without cutting a contact node, and every rank adds to cp the nodes
  whose rows it owns, law after law. Then, as for a problem built in memory: `FETISetFromOptions()`,
  `FETISetUp()`, `ContactProblemSetOperator()` with F and h, `ContactProblemSetProjector()` with Q and the
  particular solution, `ContactProblemSetFromOptions()`, `ContactProblemSolve()`.

  A file without contact rows gives no contact nodes. A file with contact rows but without a pairing (format
  version 1, or written by `FETIWrite()`) is an error, as is a pairing whose rows are out of range, of the
  wrong kind, or shared by two nodes; every error names the file.

  Level: intermediate

.seealso: `FETIWriteContact()`, `FETILoad()`, `ContactProblemAddNodes()`
@*/
PetscErrorCode FETILoadContact(FETI feti, ContactProblem cp, PetscViewer viewer)
{
  FETIContactPairing pairing;
  PetscBool          given;
  Mat                B;
  Vec                c;
  const FETIRowKind *kinds;
  PetscInt           rstart, rend, contact = 0;
  const char        *file;
  MPI_Comm           comm = PetscObjectComm((PetscObject)feti);

  PetscFunctionBegin;
  PetscValidHeaderSpecific(feti, FETI_CLASSID, 1);
  PetscValidHeaderSpecific(cp, CONTACTPROBLEM_CLASSID, 2);
  PetscValidHeaderSpecific(viewer, PETSC_VIEWER_CLASSID, 3);
  PetscCall(FETILoadWithPairing_Private(feti, viewer, &pairing, &given));
  PetscCall(PetscViewerFileGetName(viewer, &file));
  PetscCall(FETIGetConstraints(feti, &B, &c, &kinds));
  PetscCall(MatGetOwnershipRange(B, &rstart, &rend));
  for (PetscInt r = 0; r < rend - rstart; r++)
    if (kinds[r] == FETI_ROW_CONTACT_NORMAL || kinds[r] == FETI_ROW_CONTACT_TANGENTIAL) contact = 1;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &contact, 1, MPIU_INT, MPI_MAX, comm));
  PetscCheck(given || !contact, comm, PETSC_ERR_FILE_UNEXPECTED,
             "%s has contact rows but no contact pairing (a version 1 file, or written by FETIWrite()): write it with FETIWriteContact() to say which rows form a contact node",
             file ? file : "(unnamed)");
  for (ContactLaw law : {CONTACT_FRICTIONLESS, CONTACT_TRESCA, CONTACT_COULOMB}) {
    std::vector<PetscInt>  n, t1, t2;
    std::vector<PetscReal> coef;
    for (size_t k = 0; k < pairing.normal.size(); k++) {
      if (pairing.law[k] != (PetscInt)law || pairing.normal[k] < rstart || pairing.normal[k] >= rend) continue;
      PetscCallCXX(n.push_back(pairing.normal[k]));
      PetscCallCXX(t1.push_back(pairing.t1[k]));
      PetscCallCXX(t2.push_back(pairing.t2[k]));
      PetscCallCXX(coef.push_back(pairing.coef[k]));
    }
    PetscCall(ContactProblemAddNodes(cp, law, (PetscInt)n.size(), n.data(), t1.data(), t2.data(), coef.data()));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}
