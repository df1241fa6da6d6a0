/* Tutorial: contact with Coulomb friction from your own finite-element code, on non-matching meshes.

   What it does
     The contact sequel of tutorials/feti/ex1_handoff.cxx: it plays "your FEM code", which meshes and
     assembles everything itself, and uses conefeti only for FETI and the contact solve. Two elastic blocks:

       lower block  (0,2) x (0,1) x (0,1), clamped on its face x = 0 (a wall), resting on a rigid plane z = 0;
                    two subdomains, x < 1 and x > 1, glued at x = 1
       upper block  a smaller block standing on the lower one's top face, pressed down and pushed along x on
                    its own top face; one subdomain, held by nothing but its contact with the lower block

     The meshes do not match: the upper block has another spacing, so most of its bottom nodes touch the
     lower block at a point between the lower block's nodes. Each block is cut into hexahedra split into six
     tetrahedra (P1). The code builds, with its own loops,

       K_s, f_s, coordinates              per subdomain (FETISetSubdomains(), FETISetSubdomainCoordinates())
       B, c, row kinds                    gluing rows, Dirichlet rows, contact rows (FETISetConstraints())
       the contact pairing                which normal row goes with which two tangential rows, with the law
                                          and the friction coefficient (ContactProblemAddNodes())

     A contact row between the bodies ties one node of the upper block to the point below it on the lower
     block's top face: the point's displacement is the P1 interpolation of the nodes of the triangle it lies
     in, so the row has the weights of that interpolation on those nodes (it is not a unit row). Then FETI
     gives the dual problem (F, h, the projector Q and a particular solution), the ContactProblem solves it
     with the Coulomb law, the displacement u is recovered from the multipliers, and the program checks the
     mechanics itself, from u and the multipliers only: the equilibrium K u = f - B'l of every subdomain,
     the gluing and the wall, non-penetration, the sign of the contact pressure, complementarity, the
     friction cone, and the balance of each block's loads against the contact forces it receives.

   Sample runs
     contact_ex3_usercontact
     mpiexec -n 2 contact_ex3_usercontact -cells 6 -friction 0.4 -shear 0.25
     contact_ex3_usercontact -contact_coulomb_algorithm msa   (any -contact_ option of ContactProblemSetFromOptions())
     contact_ex3_usercontact -write contact.feti              (also writes the problem with its pairing:
                                                               FETIWriteContact(), docs/feti-interchange.md)

   What to expect
     A table of the checks, each a relative residual against its tolerance (-check_factor times the contact
     solver's relative tolerance -contact_rtol), the node states, and a RESULT line with the fingerprints of
     the multipliers and of u. Exit status: 0 when the solve converged and every check holds, 2 when the
     solve did not converge (as the conefeti driver), 3 when a check fails (e.g. -check_factor 1e-9 asks for
     more than the solve delivers). */
#include <conefeti.h>

#include <cmath>
#include <vector>

/* One block meshed with nx x ny x nz hexahedra: its origin, cell sizes and node numbering */
struct Block {
  PetscReal origin[3], h[3];
  PetscInt  n[3]; /* cells per direction */
  PetscInt  Node(PetscInt i, PetscInt j, PetscInt k) const { return i + (n[0] + 1) * (j + (n[1] + 1) * k); }
  PetscInt  Nodes() const { return (n[0] + 1) * (n[1] + 1) * (n[2] + 1); }
};

/* Your element routine: the P1 tetrahedron's stiffness from the gradients of its barycentric coordinates,
   Ke = V B'DB with the isotropic elasticity matrix D */
static PetscErrorCode TetStiffness(const PetscReal X[12], PetscReal E, PetscReal nu, PetscReal Ke[144])
{
  PetscReal J[3][3], inv[3][3], det, grad[4][3], D[6][6] = {}, Bm[6][12] = {};
  PetscReal lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));

  PetscFunctionBeginUser;
  for (int r = 0; r < 3; r++)
    for (int c = 0; c < 3; c++) J[r][c] = X[3 * (c + 1) + r] - X[r]; /* columns: edges from vertex 0 */
  det = J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) - J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) + J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
  PetscCheck(det > 0, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "tetrahedron with volume %g: the caller orients them positively", (double)(det / 6));
  for (int r = 0; r < 3; r++)
    for (int c = 0; c < 3; c++) {
      const int r1 = (c + 1) % 3, r2 = (c + 2) % 3, c1 = (r + 1) % 3, c2 = (r + 2) % 3;
      inv[r][c] = (J[r1][c1] * J[r2][c2] - J[r1][c2] * J[r2][c1]) / det; /* cofactor transpose */
    }
  for (int d = 0; d < 3; d++) grad[0][d] = 0;
  for (int a = 1; a < 4; a++)
    for (int d = 0; d < 3; d++) {
      grad[a][d] = inv[a - 1][d]; /* row a-1 of J^-1 is the gradient of barycentric coordinate a */
      grad[0][d] -= grad[a][d];
    }
  for (int a = 0; a < 4; a++) { /* engineering strains xx yy zz xy yz zx */
    Bm[0][3 * a] = Bm[3][3 * a + 1] = Bm[5][3 * a + 2] = grad[a][0];
    Bm[1][3 * a + 1] = Bm[3][3 * a] = Bm[4][3 * a + 2] = grad[a][1];
    Bm[2][3 * a + 2] = Bm[4][3 * a + 1] = Bm[5][3 * a] = grad[a][2];
  }
  for (int r = 0; r < 3; r++) {
    for (int c = 0; c < 3; c++) D[r][c] = lambda;
    D[r][r] += 2 * mu;
    D[r + 3][r + 3] = mu;
  }
  for (int p = 0; p < 12; p++)
    for (int q = 0; q < 12; q++) {
      PetscReal s = 0;
      for (int r = 0; r < 6; r++)
        for (int c = 0; c < 6; c++) s += Bm[r][p] * D[r][c] * Bm[c][q];
      Ke[12 * p + q] = s * det / 6;
    }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Your assembly: stiffness, coordinates and, when traction is given, the load of a uniform traction on the top
   face (each top triangle gives a third of its force to each of its nodes) */
static PetscErrorCode AssembleBlock(const Block &b, PetscReal E, PetscReal nu, const PetscReal *traction, Mat *K, Vec *f, Vec *coords)
{
  const PetscInt nn = b.Nodes();
  PetscScalar   *x, *fa;
  /* six tetrahedra per hexahedron around its diagonal from corner 0 to corner 7 (corner c has offsets c&1, c>>1&1, c>>2&1);
     the top face z = 1 is split along its diagonal from corner 4 to corner 7, into the triangles 4 5 7 and 4 6 7 */
  const PetscInt tets[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7}, {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};

  PetscFunctionBeginUser;
  PetscCall(MatCreateSeqAIJ(PETSC_COMM_SELF, 3 * nn, 3 * nn, 81, NULL, K));
  PetscCall(MatSetBlockSize(*K, 3)); /* FETI needs dofs x, y, z per node */
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, 3 * nn, f));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, 3 * nn, coords));
  PetscCall(VecGetArray(*coords, &x));
  for (PetscInt k = 0; k <= b.n[2]; k++)
    for (PetscInt j = 0; j <= b.n[1]; j++)
      for (PetscInt i = 0; i <= b.n[0]; i++) {
        const PetscInt v = b.Node(i, j, k), ijk[3] = {i, j, k};
        for (int d = 0; d < 3; d++) x[3 * v + d] = b.origin[d] + ijk[d] * b.h[d];
      }
  for (PetscInt k = 0; k < b.n[2]; k++)
    for (PetscInt j = 0; j < b.n[1]; j++)
      for (PetscInt i = 0; i < b.n[0]; i++)
        for (const auto &t : tets) {
          PetscInt  v[4];
          PetscReal X[12], Ke[144];
          for (int a = 0; a < 4; a++) {
            v[a] = b.Node(i + (t[a] & 1), j + ((t[a] >> 1) & 1), k + ((t[a] >> 2) & 1));
            for (int d = 0; d < 3; d++) X[3 * a + d] = PetscRealPart(x[3 * v[a] + d]);
          }
          /* half of these tetrahedra are listed with negative orientation: swap two vertices */
          const PetscReal e[3][3] = {{X[3] - X[0], X[4] - X[1], X[5] - X[2]}, {X[6] - X[0], X[7] - X[1], X[8] - X[2]}, {X[9] - X[0], X[10] - X[1], X[11] - X[2]}};
          const PetscReal det     = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) - e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) + e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
          if (det < 0) {
            std::swap(v[1], v[2]);
            for (int d = 0; d < 3; d++) std::swap(X[3 + d], X[6 + d]);
          }
          PetscCall(TetStiffness(X, E, nu, Ke));
          PetscCall(MatSetValuesBlocked(*K, 4, v, 4, v, Ke, ADD_VALUES));
        }
  PetscCall(VecRestoreArray(*coords, &x));
  PetscCall(MatAssemblyBegin(*K, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*K, MAT_FINAL_ASSEMBLY));
  PetscCall(VecGetArray(*f, &fa));
  if (traction)
    for (PetscInt j = 0; j < b.n[1]; j++)
      for (PetscInt i = 0; i < b.n[0]; i++) {
        const PetscInt tri[2][3] = {{b.Node(i, j, b.n[2]), b.Node(i + 1, j, b.n[2]), b.Node(i + 1, j + 1, b.n[2])}, {b.Node(i, j, b.n[2]), b.Node(i, j + 1, b.n[2]), b.Node(i + 1, j + 1, b.n[2])}};
        for (const auto &t : tri)
          for (PetscInt v : t)
            for (int d = 0; d < 3; d++) fa[3 * v + d] += traction[d] * b.h[0] * b.h[1] / 2 / 3;
      }
  PetscCall(VecRestoreArray(*f, &fa));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* One row of B under construction: global primal columns and values */
struct Row {
  std::vector<PetscInt>    cols;
  std::vector<PetscScalar> vals;
  FETIRowKind              kind;
  PetscReal                rhs;
  PetscInt                 family; /* what the row belongs to, for the force balance: 0 wall, 1 gluing, 2 plane, 3 between the blocks */
};

/* The largest over all ranks */
static PetscErrorCode Max(PetscReal *v, PetscInt n)
{
  PetscFunctionBeginUser;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, v, (PetscMPIInt)n, MPIU_REAL, MPIU_MAX, PETSC_COMM_WORLD));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscInt               cells = 4, nsub = 3;
  PetscReal              E = 2.1e11, nu = 0.3, pressure = 4e7, shear = 0.15, friction = 0.3, checkfactor = 10;
  char                   file[PETSC_MAX_PATH_LEN] = "";
  PetscBool              write                    = PETSC_FALSE;
  PetscMPIInt            size, rank;
  Block                  blk[3];
  PetscInt               dofs[3], offset[4] = {0, 0, 0, 0}, first, nlocal;
  std::vector<Mat>       K;
  std::vector<Vec>       f, coords;
  std::vector<Row>       rows;
  std::vector<PetscInt>  normal, t1, t2; /* the contact pairing of this rank's contact nodes (global rows) */
  std::vector<PetscReal> coef;
  PetscInt               nweighted = 0, example = -1;
  PetscReal              exampleweights[3] = {0, 0, 0}, examplepoint[2] = {0, 0};
  FETI                   feti;
  ContactProblem         cp;
  Mat                    B, F, Q;
  Vec                    h, e, lt, lambda, u, alpha, w;
  ContactStatistics      st;

  PetscCall(PetscInitialize(&argc, &argv, NULL, "Contact with Coulomb friction from your own FEM code"));
  PetscCall(ConeFETIInitializePackage());
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "Two blocks in contact, from your own code", "ex3_usercontact");
  PetscCall(PetscOptionsBoundedInt("-cells", "Cells along the edge of a lower subdomain (the upper block gets cells + 1 along x)", "ex3_usercontact", cells, &cells, NULL, 1));
  PetscCall(PetscOptionsReal("-pressure", "Pressure on the upper block's top face", "ex3_usercontact", pressure, &pressure, NULL));
  PetscCall(PetscOptionsReal("-shear", "Traction along x on the upper block's top face, as a fraction of -pressure", "ex3_usercontact", shear, &shear, NULL));
  PetscCall(PetscOptionsReal("-friction", "Coulomb friction coefficient on both contact surfaces", "ex3_usercontact", friction, &friction, NULL));
  PetscCall(PetscOptionsReal("-check_factor", "A check holds when its relative residual is at most this times the contact solver's -contact_rtol", "ex3_usercontact", checkfactor, &checkfactor, NULL));
  PetscCall(PetscOptionsString("-write", "Also write the FETI problem with its contact pairing to this file (FETIWriteContact())", "ex3_usercontact", file, file, sizeof(file), &write));
  PetscOptionsEnd();
  PetscCheck(pressure > 0 && !PetscIsInfOrNanReal(pressure), PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-pressure %g must be a finite positive number", (double)pressure);
  PetscCheck(!PetscIsInfOrNanReal(shear), PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-shear %g must be a finite number", (double)shear);
  PetscCheck(friction >= 0 && !PetscIsInfOrNanReal(friction), PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-friction %g must be a finite number >= 0", (double)friction);
  /* the upper block is held by friction alone along x: beyond the friction coefficient it has no equilibrium */
  PetscCheck(PetscAbsReal(shear) < friction, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-shear %g: the upper block slides off unless |shear| < -friction %g", (double)shear, (double)friction);
  PetscCheck(checkfactor > 0, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-check_factor %g must be positive", (double)checkfactor);
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  PetscCheck(size <= nsub, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "%d ranks for %d subdomains: run on at most %d ranks", size, (int)nsub, (int)nsub);

  /* 1. the meshes: lower subdomains 0 and 1 (cells^3 each), upper block 2 over (0.5,1.5) x (0.2,0.8) x (1,1.5) with
        another spacing, so that its bottom nodes fall between the lower block's top nodes */
  for (PetscInt s = 0; s < 2; s++) blk[s] = Block{{(PetscReal)s, 0, 0}, {1.0 / cells, 1.0 / cells, 1.0 / cells}, {cells, cells, cells}};
  {
    const PetscInt m[3] = {cells + 1, PetscMax(1, (3 * (cells + 1)) / 5), PetscMax(1, (cells + 1) / 2)};
    blk[2]              = Block{{0.5, 0.2, 1.0}, {1.0 / m[0], 0.6 / m[1], 0.5 / m[2]}, {m[0], m[1], m[2]}};
  }
  for (PetscInt s = 0; s < nsub; s++) {
    dofs[s]       = 3 * blk[s].Nodes();
    offset[s + 1] = offset[s] + dofs[s]; /* the primal vector: the subdomains one after the other */
  }
  first  = (nsub * rank) / size;
  nlocal = (nsub * (rank + 1)) / size - first;
  for (PetscInt s = first; s < first + nlocal; s++) {
    const PetscReal top[3] = {shear * pressure, 0, -pressure};
    Mat             Ks;
    Vec             fs, xs;
    PetscCall(AssembleBlock(blk[s], E, nu, s == 2 ? top : NULL, &Ks, &fs, &xs));
    K.push_back(Ks);
    f.push_back(fs);
    coords.push_back(xs);
  }

  /* 2. the rows of B this rank owns: those of its subdomains, so that the three rows of a contact node stay on one rank
        (a friction cone is one block of the solver's set and may not straddle ranks) */
  auto dof = [&](PetscInt s, PetscInt node, PetscInt c) { return offset[s] + 3 * node + c; };
  for (PetscInt s = first; s < first + nlocal; s++) {
    const Block &b = blk[s];
    if (s < 2) {
      for (PetscInt k = 0; k <= b.n[2]; k++)
        for (PetscInt j = 0; j <= b.n[1]; j++)
          for (PetscInt c = 0; c < 3; c++) {
            if (s == 0) rows.push_back(Row{{dof(0, b.Node(0, j, k), c)}, {1.0}, FETI_ROW_DIRICHLET, 0, 0}); /* the wall: u = 0 */
            if (s == 0)                                                                                     /* the two copies of a node of x = 1 move together; 1/sqrt(2) makes the rows orthonormal */
              rows.push_back(Row{{dof(0, b.Node(b.n[0], j, k), c), dof(1, blk[1].Node(0, j, k), c)}, {1 / PetscSqrtReal(2), -1 / PetscSqrtReal(2)}, FETI_ROW_GLUING, 0, 1});
          }
      /* the rigid plane z = 0 under the bottom nodes, i >= 1: in subdomain 0 node i = 0 is at the wall (already held),
         in subdomain 1 it is the copy of a node that has its row in subdomain 0 (two rows for one node would be dependent) */
      for (PetscInt j = 0; j <= b.n[1]; j++)
        for (PetscInt i = 1; i <= b.n[0]; i++) {
          const PetscInt v = b.Node(i, j, 0);
          normal.push_back((PetscInt)rows.size());                                    /* local for now: made global below */
          rows.push_back(Row{{dof(s, v, 2)}, {-1.0}, FETI_ROW_CONTACT_NORMAL, 0, 2}); /* z + u_z >= 0: -u_z <= z = 0 */
          rows.push_back(Row{{dof(s, v, 0)}, {1.0}, FETI_ROW_CONTACT_TANGENTIAL, 0, 2});
          rows.push_back(Row{{dof(s, v, 1)}, {1.0}, FETI_ROW_CONTACT_TANGENTIAL, 0, 2});
        }
    } else {
      /* every bottom node p of the upper block against the point q of the lower block's top face below it. q lies in the
         top triangle of a lower cell (split along its diagonal, as AssembleBlock() does), where u(q) is the P1 interpolation
         sum_i w_i u_i of the triangle's three nodes. Non-penetration of the two surfaces, (z_p + u_p,z) - (z_q + u_q,z) >= 0,
         is the row -u_p,z + sum_i w_i u_i,z <= z_p - z_q (the initial gap); the tangential rows are the relative
         displacements u_p,x - u_q,x and u_p,y - u_q,y, with the same weights, so that the multipliers of one node are the
         normal and tangential forces on the same point and the Coulomb cone |l_t| <= F l_n is the physical one */
      const Block &low = blk[0];
      for (PetscInt j = 0; j <= b.n[1]; j++)
        for (PetscInt i = 0; i <= b.n[0]; i++) {
          const PetscReal xp = b.origin[0] + i * b.h[0], yp = b.origin[1] + j * b.h[1];
          PetscInt        ci = (PetscInt)std::floor(xp / low.h[0]), cj = (PetscInt)std::floor(yp / low.h[1]);
          ci                 = PetscMin(PetscMax(ci, 0), 2 * cells - 1); /* a point on the last node line lies in the last cell */
          cj                 = PetscMin(PetscMax(cj, 0), cells - 1);
          const PetscReal xi = xp / low.h[0] - ci, eta = yp / low.h[1] - cj;
          const PetscInt  sl = ci / cells, li = ci - sl * cells, top = low.n[2]; /* the lower subdomain and its local cell */
          /* corners (0,0), (1,0), (0,1), (1,1) of the cell's top face and their weights: triangle 4 5 7 when xi >= eta, else 4 6 7 */
          const PetscInt  corner[4] = {blk[sl].Node(li, cj, top), blk[sl].Node(li + 1, cj, top), blk[sl].Node(li, cj + 1, top), blk[sl].Node(li + 1, cj + 1, top)};
          const PetscReal weight[4] = {xi >= eta ? 1 - xi : 1 - eta, xi >= eta ? xi - eta : 0, xi >= eta ? 0 : eta - xi, xi >= eta ? eta : xi};
          const PetscInt  v         = b.Node(i, j, 0);
          const PetscReal zq        = blk[sl].origin[2] + top * blk[sl].h[2];
          PetscInt        nw        = 0;
          normal.push_back((PetscInt)rows.size());
          for (PetscInt c : {2, 0, 1}) {
            Row r{{dof(2, v, c)}, {c == 2 ? -1.0 : 1.0}, c == 2 ? FETI_ROW_CONTACT_NORMAL : FETI_ROW_CONTACT_TANGENTIAL, c == 2 ? b.origin[2] - zq : 0, 3};
            nw = 0;
            for (int a = 0; a < 4; a++)
              if (weight[a] > 1e-12) { /* a point on a node or an edge has fewer than three nodes */
                r.cols.push_back(dof(sl, corner[a], c));
                r.vals.push_back(c == 2 ? weight[a] : -weight[a]);
                nw++;
              }
            rows.push_back(r);
          }
          if (nw > 1) { /* q strictly between nodes: the general case */
            nweighted++;
            if (example < 0 && nw == 3) {
              example = (PetscInt)normal.size() - 1;
              for (int a = 0, q = 0; a < 4; a++)
                if (weight[a] > 1e-12) exampleweights[q++] = weight[a];
              examplepoint[0] = xp;
              examplepoint[1] = yp;
            }
          }
        }
    }
  }
  for (PetscInt k = 0; k < (PetscInt)normal.size(); k++) { /* each normal row is followed by its two tangential rows */
    t1.push_back(normal[k] + 1);
    t2.push_back(normal[k] + 2);
    coef.push_back(friction);
  }
  {
    PetscInt nrows = (PetscInt)rows.size(), rowstart;
    PetscCallMPI(MPI_Scan(&nrows, &rowstart, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD));
    rowstart -= nrows;
    for (PetscInt k = 0; k < (PetscInt)normal.size(); k++) normal[k] += rowstart, t1[k] += rowstart, t2[k] += rowstart;
    PetscCall(MatCreateAIJ(PETSC_COMM_WORLD, nrows, offset[first + nlocal] - offset[first], PETSC_DETERMINE, offset[nsub], 4, NULL, 4, NULL, &B));
    for (PetscInt r = 0; r < nrows; r++) {
      const PetscInt g = rowstart + r;
      PetscCall(MatSetValues(B, 1, &g, (PetscInt)rows[r].cols.size(), rows[r].cols.data(), rows[r].vals.data(), INSERT_VALUES));
    }
    PetscCall(MatAssemblyBegin(B, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(B, MAT_FINAL_ASSEMBLY));
  }
  {
    std::vector<FETIRowKind> kinds;
    Vec                      c;
    PetscScalar             *ca;
    for (const Row &r : rows) kinds.push_back(r.kind);
    PetscCall(MatCreateVecs(B, NULL, &c));
    PetscCall(VecGetArray(c, &ca));
    for (size_t r = 0; r < rows.size(); r++) ca[r] = rows[r].rhs;
    PetscCall(VecRestoreArray(c, &ca));

    /* 3. hand everything to FETI (it keeps references: release ours) */
    PetscCall(FETICreate(PETSC_COMM_WORLD, &feti));
    PetscCall(FETISetSubdomains(feti, nlocal, K.data(), f.data()));
    for (PetscInt s = 0; s < nlocal; s++) {
      PetscCall(FETISetSubdomainCoordinates(feti, s, coords[s])); /* -> the six rigid-body modes of each floating subdomain */
      PetscCall(MatDestroy(&K[s]));
      PetscCall(VecDestroy(&f[s]));
    }
    PetscCall(FETISetConstraints(feti, B, c, kinds.data()));
    PetscCall(VecDestroy(&c));
  }
  /* a contact solve needs hundreds of products with F = B K+ B': dense blocks of K+ on the dofs B touches pay for their
     setup in time (ContactModel asks for -feti_kplus auto instead: a block only where it costs at most the factor's
     memory; -feti_kplus_explicit 0 or -feti_kplus auto override this call) */
  PetscCall(FETISetKplusExplicit(feti, PETSC_TRUE));
  PetscCall(FETISetFromOptions(feti));
  PetscCall(FETISetUp(feti));

  /* 4. the dual contact problem: min 1/2 l'Fl - l'h with G l = e in its projector form (Q, a particular solution), the
        normal multipliers >= 0 and the tangential pairs in the disks of radius F l_n (Coulomb) */
  PetscCall(FETIGetOperators(feti, &F, NULL, NULL, &Q));
  PetscCall(FETIGetRHS(feti, &h, &e));
  PetscCall(FETIGetParticularSolution(feti, &lt));
  PetscCall(ContactProblemCreate(PETSC_COMM_WORLD, &cp));
  PetscCall(ContactProblemSetOperator(cp, F, h));
  PetscCall(ContactProblemSetProjector(cp, Q, lt));
  PetscCall(ContactProblemAddNodes(cp, CONTACT_COULOMB, (PetscInt)normal.size(), normal.data(), t1.data(), t2.data(), coef.data()));
  PetscCall(ContactProblemSetFromOptions(cp));
  if (write) {
    PetscViewer viewer;
    PetscCall(PetscViewerBinaryOpen(PETSC_COMM_WORLD, file, FILE_MODE_WRITE, &viewer));
    PetscCall(FETIWriteContact(feti, cp, viewer));
    PetscCall(PetscViewerDestroy(&viewer));
  }

  /* 5. solve from the particular solution (G l = e holds from the start), then the primal solution: the rigid-body
        amplitudes from the multiplier of G l = e, and u = K+(f - B'l) + R alpha */
  PetscCall(FETICreateVecs(feti, &u, &lambda, &alpha));
  PetscCall(VecCopy(lt, lambda));
  PetscCall(ContactProblemSolve(cp, lambda));
  PetscCall(ContactProblemGetStatistics(cp, &st));
  PetscCall(VecDuplicate(lambda, &w));
  PetscCall(ContactProblemGetEqualityMultiplier(cp, w));
  PetscCall(FETIComputeAlphaFromEquality(feti, w, alpha));
  PetscCall(FETIRecoverPrimal(feti, lambda, alpha, u));

  /* 6. your own checks of the mechanics, from u and l only */
  {
    Vec                Bu, Ku, Btl;
    const PetscScalar *la, *bua, *ca, *kua, *fa, *btla, *xa;
    Vec                c, fload;
    PetscReal          gtol, tol, umax, lnmax = 0, fscale = 0;
    PetscReal          equilibrium = 0, gluing = 0, penetration = 0, sign = 0, complementarity = 0, cone = 0;
    PetscReal          balance[2][4][6] = {}; /* per block (lower, upper): force and moment of the loads and of each family of rows */
    PetscInt           counts[3] = {0, 0, 0}, rstart, pstart, failed = 0;
    Tao                tao;
    char               fl[17], fu[17];

    PetscCall(ContactProblemGetTao(cp, &tao));
    PetscCall(TaoGetTolerances(tao, NULL, NULL, &gtol));
    tol = checkfactor * gtol;
    PetscCall(FETIGetConstraints(feti, NULL, &c, NULL));
    PetscCall(FETIGetLoad(feti, &fload));
    PetscCall(VecDuplicate(lambda, &Bu));
    PetscCall(VecDuplicate(u, &Ku));
    PetscCall(VecDuplicate(u, &Btl));
    PetscCall(MatMult(B, u, Bu));
    PetscCall(MatMultTranspose(B, lambda, Btl));
    PetscCall(FETIApplyK(feti, u, Ku));
    PetscCall(VecNorm(u, NORM_INFINITY, &umax));
    PetscCall(MatGetOwnershipRange(B, &rstart, NULL));
    PetscCall(VecGetOwnershipRange(u, &pstart, NULL));
    PetscCall(VecGetArrayRead(lambda, &la));
    PetscCall(VecGetArrayRead(Bu, &bua));
    PetscCall(VecGetArrayRead(c, &ca));
    for (PetscInt k = 0; k < (PetscInt)normal.size(); k++) lnmax = PetscMax(lnmax, PetscRealPart(la[normal[k] - rstart]));
    PetscCall(Max(&lnmax, 1));
    /* gluing and the wall: B u = c on those rows, relative to the largest displacement */
    for (size_t r = 0; r < rows.size(); r++)
      if (rows[r].kind == FETI_ROW_GLUING || rows[r].kind == FETI_ROW_DIRICHLET) gluing = PetscMax(gluing, PetscAbsReal(PetscRealPart(bua[r] - ca[r])) / umax);
    for (PetscInt k = 0; k < (PetscInt)normal.size(); k++) {
      const PetscInt  n  = normal[k] - rstart;
      const PetscReal ln = PetscRealPart(la[n]), lt1 = PetscRealPart(la[t1[k] - rstart]), lt2 = PetscRealPart(la[t2[k] - rstart]);
      const PetscReal gap = PetscRealPart(ca[n] - bua[n]), ltn = PetscSqrtReal(lt1 * lt1 + lt2 * lt2);
      penetration     = PetscMax(penetration, -gap / umax);                                 /* N u <= c */
      sign            = PetscMax(sign, -ln / lnmax);                                        /* contact pushes */
      complementarity = PetscMax(complementarity, PetscAbsReal(ln * gap) / (lnmax * umax)); /* no force across an open gap */
      cone            = PetscMax(cone, (ltn - coef[k] * ln) / lnmax);                       /* |l_t| <= F l_n */
      /* states, at the checks' own tolerance */
      if (ln <= tol * lnmax) counts[0]++;
      else if (ltn < coef[k] * ln - tol * lnmax) counts[1]++;
      else counts[2]++;
    }
    /* the force balance of each block: the loads f and the forces -B'l of each family of rows, with their moments about the
       origin (each family's forces from l restricted to its rows) */
    {
      Vec          part;
      PetscScalar *pa;
      PetscCall(VecDuplicate(lambda, &part));
      PetscCall(VecGetArrayRead(fload, &fa));
      for (PetscInt fam = -1; fam < 4; fam++) {
        if (fam >= 0) {
          PetscCall(VecGetArray(part, &pa));
          for (size_t r = 0; r < rows.size(); r++) pa[r] = rows[r].family == fam ? la[r] : 0;
          PetscCall(VecRestoreArray(part, &pa));
          PetscCall(MatMultTranspose(B, part, Btl));
        }
        PetscCall(VecGetArrayRead(Btl, &btla));
        for (PetscInt s = 0; s < nlocal; s++) {
          const PetscInt body = first + s == 2 ? 1 : 0, o = offset[first + s] - pstart;
          PetscCall(VecGetArrayRead(coords[s], &xa));
          for (PetscInt v = 0; v < dofs[first + s] / 3; v++) {
            PetscReal force[3], *bal = balance[body][fam < 0 ? 0 : fam == 0 ? 1 : fam == 2 ? 2 : 3];
            if (fam == 1) continue; /* gluing forces cancel within a block */
            for (int d = 0; d < 3; d++) force[d] = fam < 0 ? PetscRealPart(fa[o + 3 * v + d]) : -PetscRealPart(btla[o + 3 * v + d]);
            const PetscReal x[3] = {PetscRealPart(xa[3 * v]), PetscRealPart(xa[3 * v + 1]), PetscRealPart(xa[3 * v + 2])};
            for (int d = 0; d < 3; d++) bal[d] += force[d];
            bal[3] += x[1] * force[2] - x[2] * force[1];
            bal[4] += x[2] * force[0] - x[0] * force[2];
            bal[5] += x[0] * force[1] - x[1] * force[0];
          }
          PetscCall(VecRestoreArrayRead(coords[s], &xa));
        }
        PetscCall(VecRestoreArrayRead(Btl, &btla));
      }
      PetscCall(VecRestoreArrayRead(fload, &fa));
      PetscCall(VecDestroy(&part));
      PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &balance[0][0][0], 48, MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
    }
    /* equilibrium of every subdomain, K u = f - B'l, relative to the largest of its terms */
    PetscCall(MatMultTranspose(B, lambda, Btl));
    PetscCall(VecGetArrayRead(Ku, &kua));
    PetscCall(VecGetArrayRead(fload, &fa));
    PetscCall(VecGetArrayRead(Btl, &btla));
    {
      PetscInt  nl;
      PetscReal r = 0;
      PetscCall(VecGetLocalSize(u, &nl));
      for (PetscInt i = 0; i < nl; i++) {
        r      = PetscMax(r, PetscAbsReal(PetscRealPart(kua[i] - fa[i] + btla[i])));
        fscale = PetscMax(fscale, PetscMax(PetscAbsReal(PetscRealPart(fa[i])), PetscAbsReal(PetscRealPart(btla[i]))));
      }
      PetscCall(Max(&r, 1));
      PetscCall(Max(&fscale, 1));
      equilibrium = r / fscale;
    }
    PetscCall(VecRestoreArrayRead(Ku, &kua));
    PetscCall(VecRestoreArrayRead(fload, &fa));
    PetscCall(VecRestoreArrayRead(Btl, &btla));
    PetscCall(VecRestoreArrayRead(lambda, &la));
    PetscCall(VecRestoreArrayRead(Bu, &bua));
    PetscCall(VecRestoreArrayRead(c, &ca));
    {
      PetscReal m[6] = {gluing, penetration, sign, complementarity, cone, 0};
      PetscCall(Max(m, 5));
      gluing = m[0], penetration = m[1], sign = m[2], complementarity = m[3], cone = m[4];
      PetscCall(MPIU_Allreduce(MPI_IN_PLACE, counts, 3, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD));
      PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &nweighted, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD));
    }

    /* 7. report */
    PetscInt nnodes = (PetscInt)normal.size(), m;
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &nnodes, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD));
    PetscCall(MatGetSize(B, &m, NULL));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "lower block 2 x %d^3 cells, upper block %d x %d x %d cells; %d multipliers, %d contact nodes (%d between the blocks at a point between nodes)\n",
                          (int)cells, (int)blk[2].n[0], (int)blk[2].n[1], (int)blk[2].n[2], (int)m, (int)nnodes, (int)nweighted));
    if (example >= 0) /* printed by the rank that owns the upper block */
      PetscCall(PetscSynchronizedPrintf(PETSC_COMM_WORLD, "  e.g. the upper node at x = %.4g, y = %.4g: its normal row has weights -1 and %.4g, %.4g, %.4g (norm %.4g)\n", (double)examplepoint[0],
                                        (double)examplepoint[1], (double)exampleweights[0], (double)exampleweights[1], (double)exampleweights[2],
                                        (double)PetscSqrtReal(1 + exampleweights[0] * exampleweights[0] + exampleweights[1] * exampleweights[1] + exampleweights[2] * exampleweights[2])));
    PetscCall(PetscSynchronizedFlush(PETSC_COMM_WORLD, PETSC_STDOUT));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "pipeline %s, %s: %s\n", ContactPipelines[st.pipeline], ContactCoulombAlgorithms[st.algorithm], st.reason));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "nodes: %d separated, %d stick, %d slip\n", (int)counts[0], (int)counts[1], (int)counts[2]));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "checks (relative residuals; tolerance %.1e = %g x -contact_rtol):\n", (double)tol, (double)checkfactor));
    const char     *name[]  = {"equilibrium K u = f - B'l", "gluing and wall B u = c", "non-penetration", "contact pushes (l_n >= 0)", "complementarity", "friction cone |l_t| <= F l_n"};
    const PetscReal value[] = {equilibrium, gluing, penetration, sign, complementarity, cone};
    for (int i = 0; i < 6; i++) {
      const PetscBool ok = value[i] <= tol ? PETSC_TRUE : PETSC_FALSE;
      if (!ok) failed++;
      PetscCall(PetscPrintf(PETSC_COMM_WORLD, "  %-30s %10.2e  %s\n", name[i], (double)PetscMax(value[i], 0), ok ? "ok" : "FAILED"));
    }
    /* balance: each block's loads against the forces of its constraints; relative to the largest of them */
    const char *blockname[] = {"lower", "upper"};
    for (int bo = 0; bo < 2; bo++) {
      PetscReal sum[6], scale = 0, fsum = 0, msum = 0, lever = blk[1].origin[0] + blk[1].n[0] * blk[1].h[0]; /* moments about the origin: forces times at most the lower block's length */
      for (int d = 0; d < 6; d++) sum[d] = balance[bo][0][d] + balance[bo][1][d] + balance[bo][2][d] + balance[bo][3][d];
      for (int t = 0; t < 4; t++)
        for (int d = 0; d < 3; d++) scale = PetscMax(scale, PetscAbsReal(balance[bo][t][d]));
      for (int d = 0; d < 3; d++) fsum = PetscMax(fsum, PetscAbsReal(sum[d]) / scale), msum = PetscMax(msum, PetscAbsReal(sum[3 + d]) / (scale * lever));
      const PetscBool ok = fsum <= tol && msum <= tol ? PETSC_TRUE : PETSC_FALSE;
      if (!ok) failed++;
      PetscCall(PetscPrintf(PETSC_COMM_WORLD, "  %s block: loads (%.4e, %.4e, %.4e), wall (%.4e, %.4e, %.4e), plane (%.4e, %.4e, %.4e), other block (%.4e, %.4e, %.4e)\n", blockname[bo],
                            (double)balance[bo][0][0], (double)balance[bo][0][1], (double)balance[bo][0][2], (double)balance[bo][1][0], (double)balance[bo][1][1], (double)balance[bo][1][2],
                            (double)balance[bo][2][0], (double)balance[bo][2][1], (double)balance[bo][2][2], (double)balance[bo][3][0], (double)balance[bo][3][1], (double)balance[bo][3][2]));
      PetscCall(PetscPrintf(PETSC_COMM_WORLD, "  %-30s %10.2e  %s\n", bo ? "balance of the upper block" : "balance of the lower block", (double)PetscMax(fsum, msum), ok ? "ok" : "FAILED"));
    }
    PetscCall(ConeFETIVecFingerprint(lambda, fl));
    PetscCall(ConeFETIVecFingerprint(u, fu));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "RESULT converged=%s lambda=%s u=%s\n", st.converged ? "true" : "false", fl, fu));
    if (!st.converged) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "NOT CONVERGED: %s\n", st.reason));
    else if (failed) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "FAILED: %d of 8 mechanical checks above their tolerance\n", (int)failed));
    else PetscCall(PetscPrintf(PETSC_COMM_WORLD, "all mechanical checks hold\n"));
    PetscCall(VecDestroy(&Bu));
    PetscCall(VecDestroy(&Ku));
    PetscCall(VecDestroy(&Btl));
    for (PetscInt s = 0; s < nlocal; s++) PetscCall(VecDestroy(&coords[s]));
    PetscCall(VecDestroy(&w));
    PetscCall(VecDestroy(&alpha));
    PetscCall(VecDestroy(&u));
    PetscCall(VecDestroy(&lambda));
    PetscCall(MatDestroy(&B));
    PetscCall(ContactProblemDestroy(&cp));
    PetscCall(FETIDestroy(&feti));
    PetscCall(PetscFinalize());
    return !st.converged ? 2 : failed ? 3 : 0;
  }
}
