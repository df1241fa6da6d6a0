/* HDF5 + XDMF output of a solved scene (docs/output.md).

   The HDF5 file is written in parallel through PETSc's HDF5 viewer (collective MPI-IO): every rank
   writes the nodes, tetrahedra and contact nodes it owns as its slice of each dataset, so nothing is
   gathered on one rank and the file is the same whatever the number of ranks that wrote it, up to the
   order of the subdomains' pieces. The XDMF file (small, XML) is written by rank 0.

   Both files are written under temporary names (<file>.tmp) and renamed when complete: a reader
   never sees a half-written file, and a failed write removes its temporary files and leaves any
   previous output untouched. */
#include "sceneimpl.h"
#if defined(PETSC_HAVE_HDF5)
#  include <petscviewerhdf5.h>
#endif

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/statvfs.h>

namespace {

struct Layout {
  PetscInt nnodes = 0, nelements = 0, ncontact = 0;
};

/* von Mises stress of a P1 tetrahedron from its vertices X (4x3) and nodal displacements U (4x3) */
PetscReal VonMises(const PetscReal X[12], const PetscReal U[12], PetscReal E, PetscReal nu)
{
  PetscReal D[3][3], W[3][3], Di[3][3], G[3][3], eps[3][3], sig[3][3];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      D[i][j] = X[3 * (i + 1) + j] - X[j];
      W[i][j] = U[3 * (i + 1) + j] - U[j];
    }
  const PetscReal det = D[0][0] * (D[1][1] * D[2][2] - D[1][2] * D[2][1]) - D[0][1] * (D[1][0] * D[2][2] - D[1][2] * D[2][0]) + D[0][2] * (D[1][0] * D[2][1] - D[1][1] * D[2][0]);
  Di[0][0]            = (D[1][1] * D[2][2] - D[1][2] * D[2][1]) / det;
  Di[0][1]            = (D[0][2] * D[2][1] - D[0][1] * D[2][2]) / det;
  Di[0][2]            = (D[0][1] * D[1][2] - D[0][2] * D[1][1]) / det;
  Di[1][0]            = (D[1][2] * D[2][0] - D[1][0] * D[2][2]) / det;
  Di[1][1]            = (D[0][0] * D[2][2] - D[0][2] * D[2][0]) / det;
  Di[1][2]            = (D[0][2] * D[1][0] - D[0][0] * D[1][2]) / det;
  Di[2][0]            = (D[1][0] * D[2][1] - D[1][1] * D[2][0]) / det;
  Di[2][1]            = (D[0][1] * D[2][0] - D[0][0] * D[2][1]) / det;
  Di[2][2]            = (D[0][0] * D[1][1] - D[0][1] * D[1][0]) / det;
  /* (u_k - u_0) = G (x_k - x_0): W = D G^T, so G^T = D^{-1} W */
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      G[j][i] = 0;
      for (int k = 0; k < 3; k++) G[j][i] += Di[i][k] * W[k][j];
    }
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) eps[i][j] = 0.5 * (G[i][j] + G[j][i]);
  const PetscReal lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu)), tr = eps[0][0] + eps[1][1] + eps[2][2];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) sig[i][j] = 2 * mu * eps[i][j] + (i == j ? lambda * tr : 0);
  const PetscReal a = sig[0][0] - sig[1][1], b = sig[1][1] - sig[2][2], c = sig[2][2] - sig[0][0];
  return std::sqrt(0.5 * (a * a + b * b + c * c) + 3 * (sig[0][1] * sig[0][1] + sig[1][2] * sig[1][2] + sig[0][2] * sig[0][2]));
}

PetscErrorCode ViewReal(PetscViewer v, MPI_Comm comm, const char *name, PetscInt bs, const std::vector<PetscReal> &data)
{
  Vec          x;
  PetscScalar *a;

  PetscFunctionBegin;
  PetscCall(VecCreate(comm, &x));
  PetscCall(VecSetSizes(x, (PetscInt)data.size(), PETSC_DETERMINE));
  PetscCall(VecSetBlockSize(x, bs));
  PetscCall(VecSetType(x, VECMPI));
  PetscCall(VecGetArray(x, &a));
  for (size_t i = 0; i < data.size(); i++) a[i] = data[i];
  PetscCall(VecRestoreArray(x, &a));
  PetscCall(PetscObjectSetName((PetscObject)x, name));
  PetscCall(VecView(x, v));
  PetscCall(VecDestroy(&x));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ViewInt(PetscViewer v, MPI_Comm comm, const char *name, PetscInt bs, const std::vector<PetscInt> &data)
{
  IS is;

  PetscFunctionBegin;
  PetscCall(ISCreateGeneral(comm, (PetscInt)data.size(), data.data(), PETSC_COPY_VALUES, &is));
  if (bs > 1) PetscCall(ISSetBlockSize(is, bs));
  PetscCall(PetscObjectSetName((PetscObject)is, name));
  PetscCall(ISView(is, v));
  PetscCall(ISDestroy(&is));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Closes the HDF5 file also when a write fails and the error returns early: HDF5 closes the files left
   open when MPI ends, and the second attempt to flush a file that cannot be written crashed inside
   MPI_Finalize(). Errors of the close itself are ignored: the first error is the one reported. */
struct ViewerCloser {
  PetscViewer v = NULL;
  ~ViewerCloser()
  {
    if (!v) return;
    if (PetscPushErrorHandler(PetscReturnErrorHandler, NULL)) return;
    (void)PetscViewerDestroy(&v);
    (void)PetscPopErrorHandler();
  }
};

std::string SpaceLimits(const std::string &, double);
double      DataBytes(const Layout &);
std::string Bytes(double);

PetscErrorCode WriteHDF5(ContactScene scene, const char *path, Layout &layout)
{
  Scene_Impl        &impl = *scene->impl;
  MPI_Comm           comm = PetscObjectComm((PetscObject)scene);
  ViewerCloser       closer;
  FETI               feti;
  Vec                u;
  const PetscScalar *ua;
  PetscInt           nsub, nlocal, firstsub, ustart, nodefirst, nn = 0, ne = 0;
  PetscMPIInt        size;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(ContactModelGetFETI(impl.cm, &feti));
  PetscCall(ContactModelGetSolution(impl.cm, NULL, &u));
  PetscCall(FEMGetNumSubdomains(impl.fem, &nsub, &nlocal, &firstsub));
  PetscCall(VecGetOwnershipRange(u, &ustart, NULL));
  /* the rank's volume nodes are its subdomains' nodes in primal order: the displacement is u itself */
  for (PetscInt s = 0; s < nlocal; s++) {
    PetscInt n, e;
    PetscCall(FEMGetSubdomainMesh(impl.fem, s, NULL, &n, NULL, &e, NULL));
    nn += n;
    ne += e;
  }
  {
    PetscInt ul;
    PetscCall(VecGetLocalSize(u, &ul));
    PetscCheck(ul == 3 * nn, PETSC_COMM_SELF, PETSC_ERR_PLIB, "ContactSceneWriteOutput: the primal vector has %" PetscInt_FMT " local entries, the subdomains %" PetscInt_FMT " nodes", ul, nn);
  }
  {
    PetscInt counts[2] = {nn, ne}, last[2];
    PetscCallMPI(MPI_Scan(counts, last, 2, MPIU_INT, MPI_SUM, comm));
    nodefirst = last[0] - nn;
    PetscCallMPI(MPI_Allreduce(counts, last, 2, MPIU_INT, MPI_SUM, comm));
    layout.nnodes    = last[0];
    layout.nelements = last[1];
  }
  std::vector<PetscReal> coords(3 * nn), disp(3 * nn), vm(ne);
  std::vector<PetscInt>  conn(4 * ne), subdomain(ne), body(ne);
  PetscCall(VecGetArrayRead(u, &ua));
  {
    PetscInt node = 0, elem = 0;
    for (PetscInt s = 0; s < nlocal; s++) {
      PetscInt         b, n, e, primal, coarse;
      const PetscInt  *nodes, *c;
      const PetscReal *X;
      PetscReal        E, nu;
      PetscCall(FEMGetSubdomainMesh(impl.fem, s, &b, &n, &nodes, &e, &c));
      PetscCall(FEMGetBodyNodes(impl.fem, b, NULL, &X));
      PetscCall(FETIGetSubdomainOffset(feti, s, &primal, &coarse));
      PetscCheck(primal - ustart == 3 * node, PETSC_COMM_SELF, PETSC_ERR_PLIB, "ContactSceneWriteOutput: subdomain %" PetscInt_FMT " is not where the nodes are counted", firstsub + s);
      PetscCall(FEMGetMaterial(impl.fem, b, &E, &nu)); /* -fem_E, -fem_nu may have overridden the scene */
      for (PetscInt l = 0; l < n; l++)
        for (PetscInt d = 0; d < 3; d++) {
          coords[3 * (node + l) + d] = X[3 * nodes[l] + d];
          disp[3 * (node + l) + d]   = PetscRealPart(ua[3 * (node + l) + d]);
        }
      for (PetscInt k = 0; k < e; k++) {
        PetscReal Xe[12], Ue[12];
        for (PetscInt q = 0; q < 4; q++) {
          conn[4 * (elem + k) + q] = nodefirst + node + c[4 * k + q];
          for (PetscInt d = 0; d < 3; d++) {
            Xe[3 * q + d] = coords[3 * (node + c[4 * k + q]) + d];
            Ue[3 * q + d] = disp[3 * (node + c[4 * k + q]) + d];
          }
        }
        vm[elem + k]        = VonMises(Xe, Ue, E, nu);
        subdomain[elem + k] = firstsub + s;
        body[elem + k]      = b;
      }
      node += n;
      elem += e;
    }
  }
  PetscCall(VecRestoreArrayRead(u, &ua));

  /* contact nodes owned by this rank */
  PetscInt               nc = 0, cfirst = 0;
  const PetscInt        *cbody = NULL, *cnode = NULL;
  const PetscReal       *ccoords = NULL, *carea = NULL;
  std::vector<PetscReal> pressure, traction, slip, cnormal, cgap, mweight, mpoint;
  std::vector<PetscInt>  status, cconn, mbody, mnodes;
  ContactProblem         cp;
  PetscCall(ContactModelGetContactProblem(impl.cm, &cp));
  if (cp) {
    std::vector<ContactNodeStatus> st;
    PetscCall(ContactModelGetNodes(impl.cm, &nc, &cbody, &cnode, &ccoords, &carea));
    pressure.resize(nc);
    traction.resize(3 * nc);
    slip.resize(3 * nc);
    st.resize(nc);
    PetscCall(ContactModelGetNodeStates(impl.cm, pressure.data(), traction.data(), slip.data(), st.data()));
    cnormal.resize(3 * nc);
    cgap.resize(nc);
    PetscCall(ContactModelGetNodeGeometry(impl.cm, cnormal.data(), cgap.data()));
    mbody.resize(nc);
    mnodes.resize(3 * nc);
    mweight.resize(3 * nc);
    mpoint.resize(3 * nc);
    PetscCall(ContactModelGetNodePartners(impl.cm, mbody.data(), mnodes.data(), mweight.data(), mpoint.data()));
    status.resize(nc);
    for (PetscInt i = 0; i < nc; i++) status[i] = (PetscInt)st[i];
  }
  {
    PetscInt last, total;
    PetscCallMPI(MPI_Scan(&nc, &last, 1, MPIU_INT, MPI_SUM, comm));
    PetscCallMPI(MPI_Allreduce(&nc, &total, 1, MPIU_INT, MPI_SUM, comm));
    cfirst          = last - nc;
    layout.ncontact = total;
  }
  cconn.resize(nc);
  for (PetscInt i = 0; i < nc; i++) cconn[i] = cfirst + i;

#if !defined(PETSC_HAVE_HDF5)
  SETERRQ(comm, PETSC_ERR_SUP_SYS, "-output: this PETSc is built without HDF5; rebuild PETSc with HDF5 (Debian's petsc-dev has it)");
#else
  {
    /* a file that cannot fit fails here, naming the limit, before HDF5 starts writing */
    PetscMPIInt rank;
    char        limits[1024] = "";
    PetscCallMPI(MPI_Comm_rank(comm, &rank));
    if (!rank) PetscCall(PetscStrncpy(limits, SpaceLimits(path, DataBytes(layout)).c_str(), sizeof(limits)));
    PetscCallMPI(MPI_Bcast(limits, sizeof(limits), MPI_CHAR, 0, comm));
    PetscCheck(!limits[0], comm, PETSC_ERR_FILE_WRITE, "-output: %s cannot be written: its datasets alone take %s, and %s", path, Bytes(DataBytes(layout)).c_str(), limits);
  }
  PetscCall(PetscViewerHDF5Open(comm, path, FILE_MODE_WRITE, &closer.v));
  PetscViewer v = closer.v;
  {
    char              version[32];
    PetscInt          sizes[3] = {layout.nnodes, layout.nelements, layout.ncontact};
    PetscBool         solved   = PETSC_TRUE, converged;
    ContactStatistics st;
    PetscCall(ContactModelGetStatistics(impl.cm, &st));
    converged = st.converged;
    PetscCall(PetscSNPrintf(version, sizeof(version), "%d.%d.%d", CONEFETI_VERSION_MAJOR, CONEFETI_VERSION_MINOR, CONEFETI_VERSION_PATCH));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "conefeti", PETSC_STRING, version));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "scene", PETSC_STRING, impl.name.c_str()));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "ranks", PETSC_INT, &size));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "nodes", PETSC_INT, &sizes[0]));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "tetrahedra", PETSC_INT, &sizes[1]));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "contact_nodes", PETSC_INT, &sizes[2]));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "solved", PETSC_BOOL, &solved));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "converged", PETSC_BOOL, &converged)); /* false only with -output_unconverged */
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "reason", PETSC_STRING, st.reason));
  }
  PetscCall(PetscViewerHDF5PushGroup(v, "/volume"));
  PetscCall(ViewReal(v, comm, "coordinates", 3, coords));
  PetscCall(ViewInt(v, comm, "connectivity", 4, conn));
  PetscCall(ViewReal(v, comm, "displacement", 3, disp));
  PetscCall(ViewInt(v, comm, "subdomain", 1, subdomain));
  PetscCall(ViewInt(v, comm, "body", 1, body));
  PetscCall(ViewReal(v, comm, "von_mises", 1, vm));
  PetscCall(PetscViewerHDF5PopGroup(v));
  if (layout.ncontact) {
    std::vector<PetscReal> cx(ccoords, ccoords + 3 * nc), area(carea, carea + nc);
    std::vector<PetscInt>  cb(cbody, cbody + nc), cn(cnode, cnode + nc);
    PetscCall(PetscViewerHDF5PushGroup(v, "/contact"));
    PetscCall(ViewReal(v, comm, "coordinates", 3, cx));
    PetscCall(ViewInt(v, comm, "connectivity", 1, cconn));
    PetscCall(ViewReal(v, comm, "pressure", 1, pressure));
    PetscCall(ViewReal(v, comm, "tangential_stress", 3, traction));
    PetscCall(ViewReal(v, comm, "tangential_displacement", 3, slip));
    PetscCall(ViewInt(v, comm, "status", 1, status));
    PetscCall(ViewInt(v, comm, "body", 1, cb));
    PetscCall(ViewInt(v, comm, "node", 1, cn));
    PetscCall(ViewReal(v, comm, "area", 1, area));
    PetscCall(ViewReal(v, comm, "normal", 3, cnormal));
    PetscCall(ViewReal(v, comm, "gap", 1, cgap));
    PetscCall(ViewInt(v, comm, "master_body", 1, mbody));
    PetscCall(ViewInt(v, comm, "master_nodes", 3, mnodes));
    PetscCall(ViewReal(v, comm, "master_weights", 3, mweight));
    PetscCall(ViewReal(v, comm, "master_point", 3, mpoint));
    PetscCall(PetscViewerHDF5PopGroup(v));
  }
  PetscCall(PetscViewerDestroy(&closer.v));
#endif
  PetscFunctionReturn(PETSC_SUCCESS);
}

std::string Item(const char *h5, const char *dataset, PetscInt rows, PetscInt cols, PetscBool integer)
{
  char buf[1024];
  if (cols > 1 || integer) /* PETSc's ISView writes integer datasets as rows x block size, also for block size 1 */
    snprintf(buf, sizeof(buf), "<DataItem Dimensions=\"%lld %lld\" NumberType=\"%s\" Precision=\"%d\" Format=\"HDF\">%s:%s</DataItem>", (long long)rows, (long long)cols, integer ? "Int" : "Float",
             integer ? (int)sizeof(PetscInt) : 8, h5, dataset);
  else
    snprintf(buf, sizeof(buf), "<DataItem Dimensions=\"%lld\" NumberType=\"%s\" Precision=\"%d\" Format=\"HDF\">%s:%s</DataItem>", (long long)rows, integer ? "Int" : "Float",
             integer ? (int)sizeof(PetscInt) : 8, h5, dataset);
  return buf;
}

std::string Attribute(const char *name, const char *type, const char *center, const std::string &item)
{
  return std::string("      <Attribute Name=\"") + name + "\" AttributeType=\"" + type + "\" Center=\"" + center + "\">\n        " + item + "\n      </Attribute>\n";
}

/* text for XML character data and attribute values */
std::string XMLEscape(const std::string &in)
{
  std::string out;
  for (char c : in) switch (c) {
    case '&': out += "&amp;"; break;
    case '<': out += "&lt;"; break;
    case '>': out += "&gt;"; break;
    case '"': out += "&quot;"; break;
    case '\'': out += "&apos;"; break;
    default: out += c;
    }
  return out;
}

/* text inside an XML comment: no "--" and no final '-' (entities are not expanded there) */
std::string XMLCommentText(const std::string &in)
{
  std::string out;
  for (char c : in) {
    if (c == '-' && !out.empty() && out.back() == '-') out += ' ';
    out += c;
  }
  if (!out.empty() && out.back() == '-') out += ' ';
  return out;
}

/* the XDMF text: a volume grid of tetrahedra and a contact grid of points, both referring to datasets of h5 */
std::string XDMF(const char *h5raw, const char *scene, const Layout &L)
{
  std::string       x;
  const std::string h5s = XMLEscape(h5raw);
  const char       *h5  = h5s.c_str();
  x += "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n<Xdmf Version=\"3.0\">\n  <Domain>\n";
  x += "    <!-- " + XMLCommentText(std::string("conefeti scene \"") + scene + "\": datasets in " + h5raw + " (docs/output.md)") + " -->\n";
  x += "    <Grid Name=\"volume\" GridType=\"Uniform\">\n";
  x += "      <Topology TopologyType=\"Tetrahedron\" NumberOfElements=\"" + std::to_string((long long)L.nelements) + "\">\n        " + Item(h5, "/volume/connectivity", L.nelements, 4, PETSC_TRUE) +
       "\n      </Topology>\n";
  x += "      <Geometry GeometryType=\"XYZ\">\n        " + Item(h5, "/volume/coordinates", L.nnodes, 3, PETSC_FALSE) + "\n      </Geometry>\n";
  x += Attribute("displacement", "Vector", "Node", Item(h5, "/volume/displacement", L.nnodes, 3, PETSC_FALSE));
  x += Attribute("von_mises", "Scalar", "Cell", Item(h5, "/volume/von_mises", L.nelements, 1, PETSC_FALSE));
  x += Attribute("subdomain", "Scalar", "Cell", Item(h5, "/volume/subdomain", L.nelements, 1, PETSC_TRUE));
  x += Attribute("body", "Scalar", "Cell", Item(h5, "/volume/body", L.nelements, 1, PETSC_TRUE));
  x += "    </Grid>\n";
  if (L.ncontact) {
    x += "    <Grid Name=\"contact\" GridType=\"Uniform\">\n";
    x += "      <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" + std::to_string((long long)L.ncontact) + "\" NodesPerElement=\"1\">\n        " +
         Item(h5, "/contact/connectivity", L.ncontact, 1, PETSC_TRUE) + "\n      </Topology>\n";
    x += "      <Geometry GeometryType=\"XYZ\">\n        " + Item(h5, "/contact/coordinates", L.ncontact, 3, PETSC_FALSE) + "\n      </Geometry>\n";
    x += Attribute("pressure", "Scalar", "Node", Item(h5, "/contact/pressure", L.ncontact, 1, PETSC_FALSE));
    x += Attribute("tangential_stress", "Vector", "Node", Item(h5, "/contact/tangential_stress", L.ncontact, 3, PETSC_FALSE));
    x += Attribute("tangential_displacement", "Vector", "Node", Item(h5, "/contact/tangential_displacement", L.ncontact, 3, PETSC_FALSE));
    x += Attribute("status", "Scalar", "Node", Item(h5, "/contact/status", L.ncontact, 1, PETSC_TRUE));
    x += Attribute("area", "Scalar", "Node", Item(h5, "/contact/area", L.ncontact, 1, PETSC_FALSE));
    x += Attribute("normal", "Vector", "Node", Item(h5, "/contact/normal", L.ncontact, 3, PETSC_FALSE));
    x += Attribute("gap", "Scalar", "Node", Item(h5, "/contact/gap", L.ncontact, 1, PETSC_FALSE));
    x += Attribute("body", "Scalar", "Node", Item(h5, "/contact/body", L.ncontact, 1, PETSC_TRUE));
    x += "    </Grid>\n";
  }
  x += "  </Domain>\n</Xdmf>\n";
  return x;
}

/* rank 0 writes text to path; the error (errno) is shared */
PetscErrorCode WriteText(MPI_Comm comm, const char *path, const std::string &text, const char *what)
{
  PetscMPIInt rank;
  int         err = 0;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (!rank) {
    FILE *f = fopen(path, "w");
    if (!f) err = errno ? errno : EIO;
    else {
      if (fwrite(text.data(), 1, text.size(), f) != text.size()) err = errno ? errno : EIO;
      if (fclose(f) != 0 && !err) err = errno ? errno : EIO;
    }
  }
  PetscCallMPI(MPI_Bcast(&err, 1, MPI_INT, 0, comm));
  PetscCheck(!err, comm, PETSC_ERR_FILE_WRITE, "%s: cannot write %s: %s", what, path, strerror(err));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Rank 0 replaces the pair (h5, xmf) by the temporary pair, both or neither: existing files are first
   moved aside to <name>.old, and moved back if a step fails. On error *failed names the file and errno. */
int ReplacePair(const std::string &h5tmp, const std::string &h5, const std::string &xmftmp, const std::string &xmf, std::string *failed)
{
  const std::string from[2] = {h5tmp, xmftmp}, to[2] = {h5, xmf}, old[2] = {h5 + ".old", xmf + ".old"};
  bool              moved[2] = {false, false}, placed[2] = {false, false};
  int               err = 0;
  for (int i = 0; i < 2 && !err; i++) {
    struct stat st;
    if (stat(to[i].c_str(), &st) != 0) continue; /* nothing there yet */
    if (S_ISDIR(st.st_mode)) err = EISDIR;
    else if (rename(to[i].c_str(), old[i].c_str()) != 0) err = errno ? errno : EIO;
    else moved[i] = true;
    if (err) *failed = to[i];
  }
  for (int i = 0; i < 2 && !err; i++) {
    if (rename(from[i].c_str(), to[i].c_str()) != 0) {
      err     = errno ? errno : EIO;
      *failed = to[i];
    } else placed[i] = true;
  }
  for (int i = 0; i < 2; i++) {
    if (err && placed[i]) (void)remove(to[i].c_str());
    if (moved[i]) {
      if (err) (void)rename(old[i].c_str(), to[i].c_str());
      else (void)remove(old[i].c_str());
    }
  }
  return err;
}

PetscErrorCode WriteAll(ContactScene scene, const std::string &h5, const std::string &xmf, const std::string &h5tmp, const std::string &xmftmp, PetscBool fail, Layout &layout)
{
  MPI_Comm    comm   = PetscObjectComm((PetscObject)scene);
  std::string h5name = h5;
  const char *what   = "-output";

  PetscFunctionBegin;
  /* the XDMF file refers to the HDF5 file by its name relative to the XDMF file's directory */
  const size_t slash = h5name.find_last_of('/');
  if (slash != std::string::npos) h5name = h5name.substr(slash + 1);
  PetscCall(WriteHDF5(scene, h5tmp.c_str(), layout));
  PetscCall(WriteText(comm, xmftmp.c_str(), XDMF(h5name.c_str(), scene->impl->name.c_str(), layout), what));
  PetscCheck(!fail, comm, PETSC_ERR_FILE_WRITE, "-output_test_failure: failing on purpose after writing %s and %s (tests that a failed write leaves no file behind)", h5tmp.c_str(), xmftmp.c_str());
  {
    PetscMPIInt rank;
    int         err = 0;
    std::string failed;
    PetscCallMPI(MPI_Comm_rank(comm, &rank));
    if (!rank) err = ReplacePair(h5tmp, h5, xmftmp, xmf, &failed);
    PetscCallMPI(MPI_Bcast(&err, 1, MPI_INT, 0, comm));
    PetscCheck(!err, comm, PETSC_ERR_FILE_WRITE, "%s: cannot replace %s: %s (%s and %s are left as they were)", what, rank ? "the output" : failed.c_str(), strerror(err), h5.c_str(), xmf.c_str());
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* the bytes of the datasets (docs/output.md), a lower bound of the HDF5 file's size: 6 reals per node;
   6 integers and 1 real per tetrahedron; 11 reals and 4 integers per contact node */
double DataBytes(const Layout &L) { return 8.0 * (6.0 * L.nnodes + L.nelements + 21.0 * L.ncontact) + (double)sizeof(PetscInt) * (6.0 * L.nelements + 8.0 * L.ncontact); }

/* 85.3 GB, 20.5 kB: a size for a message */
std::string Bytes(double b)
{
  const char *unit[] = {"bytes", "kB", "MB", "GB", "TB", "PB"};
  int         u      = 0;
  char        buf[64];
  while (b >= 1000 && u < 5) {
    b /= 1000;
    u++;
  }
  snprintf(buf, sizeof(buf), u ? "%.1f %s" : "%.0f %s", b, unit[u]);
  return buf;
}

std::string Directory(const std::string &file)
{
  const size_t slash = file.find_last_of('/');
  return slash == std::string::npos ? "." : slash == 0 ? "/" : file.substr(0, slash);
}

/* What keeps `file` from growing to `need` bytes, if anything rank 0 can see: a file size limit
   (ulimit -f), the free space or inodes of the file system that holds it (statvfs; a quota does not
   show there). With need 0, every limit there is. */
std::string SpaceLimits(const std::string &file, double need)
{
  std::string       text;
  char              buf[PETSC_MAX_PATH_LEN + 256];
  struct rlimit     limit;
  struct statvfs    vfs;
  const std::string dir = Directory(file);
  auto              add = [&text](const char *t) { text += (text.empty() ? "" : "; ") + std::string(t); };

  if (getrlimit(RLIMIT_FSIZE, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY && (need == 0 || (double)limit.rlim_cur < need)) {
    snprintf(buf, sizeof(buf), "the file size limit (ulimit -f) is %s", Bytes((double)limit.rlim_cur).c_str());
    add(buf);
  }
  if (statvfs(dir.c_str(), &vfs) == 0) {
    const double avail = (double)vfs.f_bavail * (double)vfs.f_frsize;
    if (vfs.f_files > 0 && vfs.f_favail == 0) {
      snprintf(buf, sizeof(buf), "no free inode on the file system that holds %s", dir.c_str());
      add(buf);
    } else if (need == 0 || avail < need) {
      snprintf(buf, sizeof(buf), "%s free on the file system that holds %s", Bytes(avail).c_str(), dir.c_str());
      add(buf);
    }
  }
  return text;
}

/* Why writing `file` failed, as far as rank 0 can tell afterwards: the errno of the failure when it
   names a cause, then the limits (SpaceLimits()) */
std::string WriteFailureCause(const std::string &file, int syserr)
{
  std::string       cause;
  const std::string limits = SpaceLimits(file, 0);

  if (syserr == ENOSPC || syserr == EFBIG || syserr == EDQUOT || syserr == EIO || syserr == EROFS || syserr == EACCES) cause = strerror(syserr);
  if (!limits.empty()) cause += (cause.empty() ? "" : "; ") + limits;
  return cause.empty() ? "cause unknown" : cause;
}

} // namespace

/*@C
  ContactSceneWriteOutput - Write the solution of a scene to <basename>.h5 (HDF5) and <basename>.xmf (XDMF, opens in ParaView).

  Collective

  Input Parameters:
+ scene    - the scene, solved
- basename - path without extension (a final .h5 or .xmf is dropped: "res.h5" writes res.h5 and res.xmf, as the driver's -output does)

  Options Database Key:
. -output_test_failure - developer (fault injection, not listed by -help): fail after writing the temporary files (tests that a failed write leaves no file)

  Notes:
  The volume grid holds every subdomain's tetrahedra with their own copies of the nodes (nodes on subdomain
  interfaces appear once per subdomain) and the cell fields subdomain, body and von Mises stress (P1: constant per
  tetrahedron). The contact grid holds the contact nodes with normal pressure, tangential stress vector,
  tangential displacement and status (0 separated, 1 stick, 2 slip). docs/output.md lists every dataset.

  The files are written under temporary names and renamed once complete: a failed write (for example an
  unwritable directory, a full disk, a file size limit) gives an error naming the file and, as far as it
  can be told afterwards, the cause (errno, ulimit -f, the free space), and leaves no partial file; a run
  killed while writing leaves at most the temporary files <basename>.h5.tmp and <basename>.xmf.tmp.

  Level: beginner

.seealso: `ContactSceneSolve()`, `ContactSceneGetSummary()`
@*/
PetscErrorCode ContactSceneWriteOutput(ContactScene scene, const char basename[])
{
  MPI_Comm       comm;
  PetscErrorCode ierr;
  PetscMPIInt    rank;
  PetscBool      fail = PETSC_FALSE;
  std::string    h5, xmf, h5tmp, xmftmp;
  Layout         layout;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(scene, CONTACTSCENE_CLASSID, 1);
  comm = PetscObjectComm((PetscObject)scene);
  PetscCheck(scene->impl->solved, comm, PETSC_ERR_ORDER, "Call ContactSceneSolve() before ContactSceneWriteOutput()");
  PetscCheck(basename && basename[0], comm, PETSC_ERR_ARG_WRONG, "-output needs a base name (the files are <basename>.h5 and <basename>.xmf)");
  PetscCheck(basename[strlen(basename) - 1] != '/', comm, PETSC_ERR_ARG_WRONG, "-output %s: a base name, not a directory (the files are <basename>.h5 and <basename>.xmf)", basename);
  /* a developer's fault injection, deliberately not among the options -help lists */
  {
    const char *prefix;
    PetscCall(PetscObjectGetOptionsPrefix((PetscObject)scene, &prefix));
    PetscCall(PetscOptionsGetBool(((PetscObject)scene)->options, prefix, "-output_test_failure", &fail, NULL));
  }
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  std::string base(basename); /* a name of one of the two files: res.h5 would have written res.h5.h5 and res.h5.xmf */
  for (const std::string ext : {".h5", ".xmf"})
    if (base.size() > ext.size() && !base.compare(base.size() - ext.size(), ext.size(), ext)) {
      base.resize(base.size() - ext.size());
      break;
    }
  h5     = base + ".h5";
  xmf    = base + ".xmf";
  h5tmp  = h5 + ".tmp";
  xmftmp = xmf + ".tmp";
  PetscCall(PetscLogEventBegin(CONTACTSCENE_Output, scene, 0, 0, 0));
  /* a clear message before HDF5 prints its own error stack: can the directory be written? */
  PetscCall(WriteText(comm, xmftmp.c_str(), "", "-output"));
#if defined(PETSC_HAVE_HDF5)
  /* HDF5's own error stack (dozens of lines for a full disk) would bury the message naming the file */
  H5E_auto2_t h5func = NULL;
  void       *h5data = NULL;
  const bool  quiet  = H5Eget_auto2(H5E_DEFAULT, &h5func, &h5data) >= 0 && H5Eset_auto2(H5E_DEFAULT, NULL, NULL) >= 0;
#endif
  errno = 0;
  ierr  = WriteAll(scene, h5, xmf, h5tmp, xmftmp, fail, layout);
  {
    /* the errno of a failed write(), if nothing has overwritten it since; the ranks agree on the outcome
       (a collective MPI-IO write can fail on the ranks that wrote and succeed on the others) */
    const int   syserr = errno;
    PetscMPIInt code   = (PetscMPIInt)ierr;
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &code, 1, MPI_INT, MPI_MAX, comm));
#if defined(PETSC_HAVE_HDF5)
    if (quiet) (void)H5Eset_auto2(H5E_DEFAULT, h5func, h5data);
#endif
    if (code) {
      char        cause[1024] = "", said[1100] = "";
      char       *inner = NULL;
      const char *kind  = NULL;
      if (!rank) {
        (void)remove(h5tmp.c_str());
        (void)remove(xmftmp.c_str());
        PetscCall(PetscStrncpy(cause, WriteFailureCause(h5tmp, syserr).c_str(), sizeof(cause)));
      }
      PetscCallMPI(MPI_Bcast(cause, sizeof(cause), MPI_CHAR, 0, comm));
      /* the message of the error that stopped the write (HDF5's, through PETSc's viewer) */
      if (ierr && !PetscErrorMessage(ierr, &kind, &inner) && inner && inner[0]) snprintf(said, sizeof(said), " (the write ended with: %s)", inner);
      PetscCheck(ierr == PETSC_ERR_FILE_WRITE || fail, comm, PETSC_ERR_FILE_WRITE, "-output: writing %s failed: %s; the previous %s and %s, if any, are left as they were%s", h5tmp.c_str(), cause,
                 h5.c_str(), xmf.c_str(), said);
      PetscCall(ierr);
    }
  }
  PetscCall(PetscLogEventEnd(CONTACTSCENE_Output, scene, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}
