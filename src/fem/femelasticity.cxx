/* P1 linear elasticity on tetrahedra: element stiffness, volume loads, surface tractions. */
#include <conefeti/private/femimpl.h>

#include <cmath>

/* Gradients of the four barycentric functions and the volume of a tetrahedron */
static PetscErrorCode TetGradients(const PetscReal X[12], PetscReal grad[4][3], PetscReal *volume)
{
  PetscReal J[3][3], inv[3][3], det;

  PetscFunctionBegin;
  for (PetscInt r = 0; r < 3; r++)
    for (PetscInt c = 0; c < 3; c++) J[r][c] = X[3 * (c + 1) + r] - X[r]; /* column c: x_{c+1} - x_0 */
  det = J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) - J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) + J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
  PetscCheck(det > 0, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "Tetrahedron with non-positive volume %g (degenerate or inverted element)", (double)(det / 6));
  inv[0][0] = (J[1][1] * J[2][2] - J[1][2] * J[2][1]) / det;
  inv[0][1] = (J[0][2] * J[2][1] - J[0][1] * J[2][2]) / det;
  inv[0][2] = (J[0][1] * J[1][2] - J[0][2] * J[1][1]) / det;
  inv[1][0] = (J[1][2] * J[2][0] - J[1][0] * J[2][2]) / det;
  inv[1][1] = (J[0][0] * J[2][2] - J[0][2] * J[2][0]) / det;
  inv[1][2] = (J[0][2] * J[1][0] - J[0][0] * J[1][2]) / det;
  inv[2][0] = (J[1][0] * J[2][1] - J[1][1] * J[2][0]) / det;
  inv[2][1] = (J[0][1] * J[2][0] - J[0][0] * J[2][1]) / det;
  inv[2][2] = (J[0][0] * J[1][1] - J[0][1] * J[1][0]) / det;
  /* grad phi_{a+1} = J^{-T} e_a, i.e. row a of J^{-1}; grad phi_0 = -sum */
  for (PetscInt d = 0; d < 3; d++) {
    grad[0][d] = 0;
    for (PetscInt a = 0; a < 3; a++) {
      grad[a + 1][d] = inv[a][d];
      grad[0][d] -= inv[a][d];
    }
  }
  *volume = det / 6.0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMElementStiffness - Stiffness matrix of a P1 (linear) tetrahedron for isotropic linear elasticity.

  Not Collective

  Input Parameters:
+ X  - the coordinates of the 4 vertices, 3 per vertex, positively oriented
. E  - Young's modulus (> 0)
- nu - Poisson's ratio (-1 < nu < 1/2)

  Output Parameters:
+ Ke     - the 12 x 12 matrix, row-major, dofs interleaved (vertex a, component i is row 3a + i)
- volume - the element volume (may be NULL)

  Notes:
  K(3a+i, 3b+j) = V [lambda d_i phi_a d_j phi_b + mu (d_i phi_b d_j phi_a + delta_ij grad phi_a . grad phi_b)],
  with the Lame constants lambda = E nu / ((1 + nu)(1 - 2 nu)) and mu = E / (2 (1 + nu)).

  Level: developer

.seealso: `FEMAssembleGlobal()`, `FEMCreateFETI()`
@*/
PetscErrorCode FEMElementStiffness(const PetscReal X[12], PetscReal E, PetscReal nu, PetscReal Ke[144], PetscReal *volume)
{
  PetscReal grad[4][3], V;

  PetscFunctionBegin;
  PetscCheck(E > 0, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "Young's modulus E = %g must be positive", (double)E);
  PetscCheck(nu > -1 && nu < 0.5, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "Poisson's ratio nu = %g must lie in (-1, 0.5)", (double)nu);
  PetscCall(TetGradients(X, grad, &V));
  const PetscReal lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
  for (PetscInt a = 0; a < 4; a++)
    for (PetscInt b = 0; b < 4; b++) {
      const PetscReal dot = grad[a][0] * grad[b][0] + grad[a][1] * grad[b][1] + grad[a][2] * grad[b][2];
      for (PetscInt i = 0; i < 3; i++)
        for (PetscInt j = 0; j < 3; j++) Ke[(3 * a + i) * 12 + 3 * b + j] = V * (lambda * grad[a][i] * grad[b][j] + mu * (grad[b][i] * grad[a][j] + (i == j ? dot : 0)));
    }
  if (volume) *volume = V;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Volume load of one tetrahedron: int f . phi_a, by the 4-point rule exact for quadratics */
PetscErrorCode FEMElementLoad(const PetscReal X[12], FEMVectorField field, void *ctx, PetscReal fe[12])
{
  const PetscReal a = 0.5854101966249685, b = 0.1381966011250105;
  PetscReal       grad[4][3], V;

  PetscFunctionBegin;
  PetscCall(TetGradients(X, grad, &V));
  for (PetscInt i = 0; i < 12; i++) fe[i] = 0;
  for (PetscInt q = 0; q < 4; q++) {
    PetscReal bary[4] = {b, b, b, b}, x[3] = {0, 0, 0}, f[3] = {0, 0, 0};
    bary[q] = a;
    for (PetscInt v = 0; v < 4; v++)
      for (PetscInt d = 0; d < 3; d++) x[d] += bary[v] * X[3 * v + d];
    PetscCall(field(x, f, ctx));
    for (PetscInt v = 0; v < 4; v++)
      for (PetscInt d = 0; d < 3; d++) fe[3 * v + d] += 0.25 * V * bary[v] * f[d];
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Surface load of one triangle: int t . phi_a, by the edge-midpoint rule exact for quadratics.
   field == NULL means the constant traction value[]. */
PetscErrorCode FEMTriangleLoad(const PetscReal X[9], PetscReal area, FEMVectorField field, void *ctx, const PetscReal value[3], PetscReal fe[9])
{
  PetscFunctionBegin;
  for (PetscInt i = 0; i < 9; i++) fe[i] = 0;
  for (PetscInt e = 0; e < 3; e++) {
    const PetscInt p = e, q   = (e + 1) % 3; /* midpoint of edge p-q: phi_p = phi_q = 1/2 */
    PetscReal      x[3], t[3] = {value[0], value[1], value[2]};
    for (PetscInt d = 0; d < 3; d++) x[d] = 0.5 * (X[3 * p + d] + X[3 * q + d]);
    if (field) PetscCall(field(x, t, ctx));
    for (PetscInt d = 0; d < 3; d++) {
      fe[3 * p + d] += area / 3.0 * 0.5 * t[d];
      fe[3 * q + d] += area / 3.0 * 0.5 * t[d];
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}
