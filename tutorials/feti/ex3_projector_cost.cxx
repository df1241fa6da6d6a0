/* What the projector costs beside F: CPU time per product with F, G = R'B', G' = B R, the coarse solve with G G'
   and Q = G'(G G')^-1 G, on the FETI problem of a contact scene (the driver's options: the scene is set up, not
   solved). The products are interleaved, so that the load of a shared machine hits them alike: compare their
   ratios, not the milliseconds of two runs.

   Run (from the repository root; docs/scale.md, "The projector's cost"):
     build/tutorials/feti/feti_ex3_projector_cost -options_file petsc-options/brick.opts -scene_refine 24 -scene_body0_subdomains 12,4,4
   Expect one line: the sizes, then milliseconds of CPU per product (rank 0's) and Q / F, e.g. at n = 135 000 a
   Q of about a twentieth of an F product (0.047 in docs/scale.md). -ex3_repeat sets the repetitions (F is timed every tenth). */
#include <conefeti.h>
#include <ctime>

static double CPUSeconds(void)
{
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

int main(int argc, char **argv)
{
  ContactScene scene;
  ContactModel cm;
  FETI         feti;
  Mat          F, G, Q;
  Vec          d1, d2, c1, c2;
  PetscRandom  rnd;
  PetscInt     repeat = 100, nprimal, m, ncoarse;
  double       t[5]   = {0, 0, 0, 0, 0}; /* F, G, G', coarse, Q */

  PetscCall(PetscInitialize(&argc, &argv, NULL, "CPU time of the FETI projector's parts against F"));
  PetscCall(ConeFETIInitializePackage());
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "Projector cost", "FETI");
  PetscCall(PetscOptionsInt("-ex3_repeat", "Products of each kind to time (F: every tenth)", "FETIGetOperators", repeat, &repeat, NULL));
  PetscOptionsEnd();
  PetscCheck(repeat >= 10, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-ex3_repeat %" PetscInt_FMT ": at least 10", repeat);
  PetscCall(ContactSceneCreateFromOptions(PETSC_COMM_WORLD, NULL, &scene));
  PetscCall(ContactSceneSetUp(scene));
  PetscCall(ContactSceneGetContactModel(scene, &cm));
  PetscCall(ContactModelGetFETI(cm, &feti));
  PetscCall(FETIGetOperators(feti, &F, &G, NULL, &Q));
  PetscCall(FETIGetSizes(feti, &nprimal, &m, &ncoarse));
  PetscCall(FETICreateVecs(feti, NULL, &d1, &c1));
  PetscCall(VecDuplicate(d1, &d2));
  PetscCall(VecDuplicate(c1, &c2));
  PetscCall(PetscRandomCreate(PETSC_COMM_WORLD, &rnd));
  PetscCall(PetscRandomSetFromOptions(rnd));
  PetscCall(VecSetRandom(d1, rnd));
  PetscCall(VecSetRandom(c1, rnd));
  for (PetscInt it = 0; it < repeat; it++) {
    double a = CPUSeconds(), b;
    if (it % 10 == 0) {
      PetscCall(MatMult(F, d1, d2));
      b = CPUSeconds();
      t[0] += b - a;
      a = b;
    }
    PetscCall(MatMult(G, d1, c2));
    b = CPUSeconds();
    t[1] += b - a;
    PetscCall(MatMultTranspose(G, c1, d2));
    a = CPUSeconds();
    t[2] += a - b;
    PetscCall(FETIApplyCoarseInverse(feti, c1, c2));
    b = CPUSeconds();
    t[3] += b - a;
    PetscCall(MatMult(Q, d1, d2));
    a = CPUSeconds();
    t[4] += a - b;
  }
  const double nF = (double)((repeat + 9) / 10), n = (double)repeat;
  PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                        "primal %" PetscInt_FMT ", dual %" PetscInt_FMT ", coarse %" PetscInt_FMT "; CPU ms per product (rank 0): F %.3f, G %.3f, G' %.3f, coarse solve %.3f, Q %.3f; Q / F %.3f\n",
                        nprimal, m, ncoarse, 1e3 * t[0] / nF, 1e3 * t[1] / n, 1e3 * t[2] / n, 1e3 * t[3] / n, 1e3 * t[4] / n, (t[4] / n) / (t[0] / nF)));
  PetscCall(PetscRandomDestroy(&rnd));
  PetscCall(VecDestroy(&d1));
  PetscCall(VecDestroy(&d2));
  PetscCall(VecDestroy(&c1));
  PetscCall(VecDestroy(&c2));
  PetscCall(ContactSceneDestroy(&scene));
  PetscCall(PetscFinalize());
  return 0;
}
