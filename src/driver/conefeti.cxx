/* conefeti: solve a scene (3D contact of elastic bodies with Coulomb friction, by FETI) given as
   options, usually a commented options file of petsc-options/ (docs/scenes.md).

   Sample runs:
     conefeti -options_file petsc-options/brick.opts                    (the seed paper's brick, F = 0.3)
     conefeti -options_file petsc-options/brick.opts -scene_refine 8    (n = 5832)
     mpiexec -n 3 conefeti -options_file petsc-options/twobodies.opts -output twobodies
     conefeti -options_file petsc-options/brick.opts -help              (every option of the scene and the solvers)

   It prints the pipeline the scene calls for before solving (linear, frictionless, Tresca or Coulomb
   with its algorithm), then a table with the counts of the seed paper's tables (n, m, Iter,
   n_A = QPP + QPQ), times, the mechanical residuals and the contact node states, and one JSON line
   starting with {"conefeti": (docs/output.md). With -output <basename> it writes <basename>.h5 and
   <basename>.xmf (open the .xmf in ParaView).

   Exit status: 0 when the solve converged; 2 when it did not (iteration limit, or no equilibrium: the
   stated reason is printed, the JSON line has "converged":false, no output is written unless
   -output_unconverged); 1 for bad input or a failure: one message naming the option, file or value, and
   a line of hint (-traceback prints PETSc's full report instead; src/driver/errors.cxx). */
#include <conefeti.h>
#include <conefeti/compat.h>
#include "driver.h"
#include <cerrno>
#include <climits>
#include <cstdlib>
#include <csignal>
#include <cstring>
#include <string>
#include <vector>
#include <sys/stat.h>

static const char usage[] = "conefeti: 3D contact problems of linear elasticity with Coulomb friction by FETI.\n"
                            "Give a scene with -options_file petsc-options/<scene>.opts (docs/scenes.md).\n\n";

/* Rank 0 creates and removes `tmp`, the temporary name the run writes first, and checks that no file it renames
   to is a directory: run before the solve, so that a missing directory, a read-only place or a directory in the
   way fails in a second, naming the option, and not after a long solve */
static PetscErrorCode CheckWritable(MPI_Comm comm, const char *option, const std::string &tmp, const std::vector<std::string> &finals)
{
  PetscMPIInt rank;
  int         err[2] = {0, -1}; /* errno, and which final file (-1: tmp) */

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (!rank) {
    struct stat st;
    for (size_t k = 0; k < finals.size() && !err[0]; k++)
      if (stat(finals[k].c_str(), &st) == 0 && S_ISDIR(st.st_mode)) {
        err[0] = EISDIR;
        err[1] = (int)k;
      }
    FILE *f = err[0] ? NULL : fopen(tmp.c_str(), "w");
    if (!err[0] && !f) err[0] = errno ? errno : EIO;
    else if (f) {
      if (fclose(f) != 0) err[0] = errno ? errno : EIO;
      (void)remove(tmp.c_str());
    }
  }
  PetscCallMPI(MPI_Bcast(err, 2, MPI_INT, 0, comm));
  PetscCheck(!err[0], comm, PETSC_ERR_FILE_WRITE, "%s: cannot write %s: %s (checked before the solve)", option, err[1] < 0 ? tmp.c_str() : finals[err[1]].c_str(), strerror(err[0]));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Whether two paths name one file (which need not exist yet): the same name in the same directory, the directories
   compared after realpath() (./a.h5 and a.h5, dir/../a.h5) */
static bool SameFile(const std::string &a, const std::string &b)
{
  const auto canonical = [](const std::string &path) {
    const size_t      slash = path.find_last_of('/');
    const std::string dir   = slash == std::string::npos ? "." : slash == 0 ? "/" : path.substr(0, slash);
    char              buf[PATH_MAX];
    return realpath(dir.c_str(), buf) ? std::string(buf) + "/" + path.substr(slash == std::string::npos ? 0 : slash + 1) : path;
  };
  return canonical(a) == canonical(b);
}

/* rank 0 writes the JSON line to <path>.tmp and renames it: a reader never sees half a line */
static PetscErrorCode WriteJSONFile(MPI_Comm comm, const char *path, const char *json)
{
  PetscMPIInt       rank;
  int               err = 0;
  const std::string tmp = std::string(path) + ".tmp";

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (!rank) {
    FILE *f = fopen(tmp.c_str(), "w");
    if (!f) err = errno ? errno : EIO;
    else {
      if (fprintf(f, "%s\n", json) < 0) err = errno ? errno : EIO;
      if (fclose(f) != 0 && !err) err = errno ? errno : EIO;
      if (!err && rename(tmp.c_str(), path) != 0) err = errno ? errno : EIO;
      if (err) (void)remove(tmp.c_str());
    }
  }
  PetscCallMPI(MPI_Bcast(&err, 1, MPI_INT, 0, comm));
  PetscCheck(!err, comm, PETSC_ERR_FILE_WRITE, "-summary_json: cannot write %s: %s", path, strerror(err));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A misspelt solver option in a scene file (-contact_coulomb_algoritm merged) would otherwise run the
   default method without a word: this PETSc build does not print -options_left by default. The scene's
   own options are checked strictly when it is read; the others may legitimately go unused (contact
   options in a scene without contact), so they get a warning, as a PETSc debug build gives. */
static PetscErrorCode WarnUnusedOptions(MPI_Comm comm)
{
  PetscInt  n;
  char    **names, **values;
  PetscBool given;

  PetscFunctionBegin;
  PetscCall(PetscOptionsHasName(NULL, NULL, "-options_left", &given)); /* PETSc reports them itself (or was told not to) */
  if (given) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscOptionsLeftGet(NULL, &n, &names, &values));
  if (n) PetscCall(PetscPrintf(comm, "WARNING: %" PetscInt_FMT " option(s) set but not used (misspelt, or not needed by this scene; -options_left 0 silences this):\n", n));
  for (PetscInt i = 0; i < n; i++) PetscCall(PetscPrintf(comm, "  -%s %s\n", names[i], values[i] ? values[i] : ""));
  PetscCall(PetscOptionsLeftRestore(NULL, &n, &names, &values));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* -output names a base name, not a directory: "results/" or an existing directory would be found only
   when the output is written, after the solve (rank 0 looks, the answer is shared) */
static PetscErrorCode CheckBaseName(MPI_Comm comm, const char *output)
{
  PetscMPIInt       rank;
  int               dir = 0;
  const std::string base(output);
  const size_t      slash = base.find_last_of('/');
  const std::string last  = slash == std::string::npos ? base : base.substr(slash + 1);

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (!rank) {
    struct stat st;
    dir = last.empty() || last == "." || last == ".." || (stat(output, &st) == 0 && S_ISDIR(st.st_mode));
  }
  PetscCallMPI(MPI_Bcast(&dir, 1, MPI_INT, 0, comm));
  PetscCheck(!dir, comm, PETSC_ERR_ARG_WRONG, "-output %s: a directory; give a base name, e.g. -output %s%sbrick writes %s%sbrick.h5 and %s%sbrick.xmf (checked before the solve)", output, output,
             base.back() == '/' ? "" : "/", output, base.back() == '/' ? "" : "/", output, base.back() == '/' ? "" : "/");
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The program; main() reports its error. *status: 0 converged (or -help without a scene), 2 not converged */
static PetscErrorCode Run(PetscBool traceback, int *status)
{
  ContactScene            scene;
  ContactSceneSummary     summary;
  ContactPipeline         pipeline;
  ContactCoulombAlgorithm algorithm;
  char                    output[PETSC_MAX_PATH_LEN] = "", jsonfile[PETSC_MAX_PATH_LEN] = "", description[256], json[16384];
  PetscBool               hasoutput = PETSC_FALSE, hasjson = PETSC_FALSE, table = PETSC_TRUE, unconverged = PETSC_FALSE, help, quiet = PETSC_FALSE;
  PetscInt                progress        = DRIVER_PROGRESS_AUTO;
  const char *const       progressmodes[] = {"auto", "terminal", "log", "none"};
  PetscInt                major, minor, patch;
  MPI_Comm                comm = PETSC_COMM_WORLD;

  PetscFunctionBegin;
  *status = 0;
  PetscCall(ConeFETIInitializePackage());
  PetscOptionsBegin(comm, NULL, "conefeti driver", "conefeti");
  PetscCall(PetscOptionsString("-output", "Write <basename>.h5 and <basename>.xmf (open the .xmf in ParaView; a name ending in .h5 or .xmf stands for its base name)", "ContactSceneWriteOutput",
                               output, output, sizeof(output), &hasoutput));
  PetscCall(PetscOptionsBool("-output_unconverged", "Write the output even when the solve did not converge", "ContactSceneWriteOutput", unconverged, &unconverged, NULL));
  PetscCall(PetscOptionsString("-summary_json", "Also write the JSON summary line to this file", "ContactSceneSummaryViewJSON", jsonfile, jsonfile, sizeof(jsonfile), &hasjson));
  PetscCall(PetscOptionsBool("-summary_table", "Print the human-readable table", "ContactSceneSummaryView", table, &table, NULL));
  PetscCall(PetscOptionsEList("-progress",
                              "Progress of the setup and the solve: auto (terminal when stdout is one, else log), terminal (one line rewritten), log (one line per phase with its time), none",
                              "ContactSceneSetProgress", progressmodes, 4, progressmodes[progress], &progress, NULL));
  PetscCall(PetscOptionsBool("-quiet", "Print no progress (the same as -progress none)", "ContactSceneSetProgress", quiet, &quiet, NULL));
  PetscCall(PetscOptionsBool("-traceback", "On an error, print PETSc's full report (traceback, options, configure line) instead of the message alone", "", traceback, &traceback, NULL));
  PetscOptionsEnd();
  PetscCheck(!hasoutput || output[0], comm, PETSC_ERR_ARG_WRONG, "-output needs a base name: -output results/brick writes results/brick.h5 and results/brick.xmf");
  if (hasoutput) { /* -output res.h5 (or res.xmf) names one of the two files: it wrote res.h5.h5 and res.h5.xmf */
    const size_t len = std::strlen(output);
    for (const char *ext : {".h5", ".xmf"})
      if (len > std::strlen(ext) && !std::strcmp(output + len - std::strlen(ext), ext)) {
        output[len - std::strlen(ext)] = 0;
        break;
      }
  }
  PetscCheck(!hasjson || jsonfile[0], comm, PETSC_ERR_ARG_WRONG, "-summary_json needs a file name");

  PetscCall(ContactSceneCreateFromOptions(comm, NULL, &scene));
  PetscCall(PetscOptionsHasHelp(NULL, &help));
  {
    PetscBool hasbody;
    PetscCall(PetscOptionsHasName(NULL, NULL, "-scene_body0_cells", &hasbody));
    if (help && !hasbody) {
      /* -help without a scene: the scene and driver options are listed; the solvers' need a scene */
      PetscCall(PetscPrintf(comm, "\nconefeti: no scene given; run with -options_file petsc-options/brick.opts -help to list the solver options too (docs/scenes.md)\n"));
      PetscCall(ContactSceneDestroy(&scene));
      PetscFunctionReturn(PETSC_SUCCESS);
    }
  }
  if (hasoutput) PetscCall(CheckBaseName(comm, output));
  if (hasoutput) PetscCall(CheckWritable(comm, "-output", std::string(output) + ".xmf.tmp", {std::string(output) + ".h5", std::string(output) + ".xmf"}));
  if (hasjson) PetscCall(CheckWritable(comm, "-summary_json", std::string(jsonfile) + ".tmp", {jsonfile}));
  if (hasoutput && hasjson) {
    int         clash = 0; /* rank 0's file system decides, as for the writes */
    PetscMPIInt rank;
    PetscCallMPI(MPI_Comm_rank(comm, &rank));
    if (!rank) clash = SameFile(jsonfile, std::string(output) + ".h5") || SameFile(jsonfile, std::string(output) + ".xmf");
    PetscCallMPI(MPI_Bcast(&clash, 1, MPI_INT, 0, comm));
    PetscCheck(!clash, comm, PETSC_ERR_ARG_INCOMP, "-summary_json %s is a file that -output %s writes: give them different names", jsonfile, output);
  }
  PetscCall(ConeFETIGetVersion(&major, &minor, &patch));
  PetscCall(DriverProgressSet(scene, quiet ? DRIVER_PROGRESS_NONE : (DriverProgressMode)progress));
  PetscCall(ContactSceneSetUp(scene));
  PetscCall(DriverProgressClear());
  PetscCall(ContactSceneGetPipelineDescription(scene, &pipeline, &algorithm, description, sizeof(description)));
  PetscCall(PetscPrintf(comm, "conefeti %" PetscInt_FMT ".%" PetscInt_FMT ".%" PetscInt_FMT ": pipeline %s\n", major, minor, patch, description));
  PetscCall(ContactSceneSolve(scene));
  PetscCall(DriverProgressClear());
  PetscCall(ContactSceneGetSummary(scene, &summary));
  if (table) PetscCall(ContactSceneSummaryView(&summary, NULL));
  PetscCall(ContactSceneSummaryToJSON(&summary, json, sizeof(json)));
  PetscCall(PetscPrintf(comm, "%s\n", json));
  if (hasjson) PetscCall(WriteJSONFile(comm, jsonfile, json));
  if (hasoutput) {
    if (summary.converged || unconverged) {
      PetscCall(ContactSceneWriteOutput(scene, output));
      PetscCall(PetscPrintf(comm, "output: %s.h5, %s.xmf%s\n", output, output, summary.converged ? "" : " (NOT CONVERGED)"));
    } else PetscCall(PetscPrintf(comm, "output: not written, the solve did not converge (-output_unconverged writes it anyway)\n"));
  }
  PetscCall(ContactSceneDestroy(&scene));
  PetscCall(WarnUnusedOptions(comm));
  *status = summary.converged ? 0 : 2;
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscErrorCode ierr;
  PetscBool      traceback = PETSC_FALSE, handler = PETSC_FALSE;
  MPI_Comm       agree;
  int            status = 0;

  DriverProgressNoteLauncher(); /* before MPI_Init() sets the launcher's variables itself */
  /* MPI before PETSc: a problem found before PetscInitialize() is then reported once, not by every rank */
  if (MPI_Init(&argc, &argv) != MPI_SUCCESS) return 1;
  {
    std::string message;
    PetscMPIInt rank, size;
    int         ok = DriverCheckOptionsFiles(argc, argv, &message), first;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    const int me = ok ? size : rank;
    MPI_Allreduce(&me, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    if (first < size) { /* the first rank that found the problem reports it; the others wait for it (errors.cxx) */
      if (first == rank) fprintf(stderr, "conefeti: error: %s\n", message.c_str());
      fflush(stderr);
      MPI_Barrier(MPI_COMM_WORLD);
      MPI_Finalize();
      return first == rank ? 1 : 0;
    }
  }
  ierr = PetscInitialize(&argc, &argv, NULL, usage);
  if (ierr) return 1; /* PETSc has reported it */
  /* a write beyond the file size limit (ulimit -f) fails with EFBIG and is reported naming the file,
     instead of killing the process without a word */
  (void)signal(SIGXFSZ, SIG_IGN);
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-traceback", &traceback, NULL));
  for (const char *name : {"-on_error_abort", "-on_error_attach_debugger", "-on_error_emacs", "-start_in_debugger", "-stop_for_debugger"}) {
    PetscBool has;
    PetscCall(PetscOptionsHasName(NULL, NULL, name, &has));
    handler = (PetscBool)(handler || has); /* PETSc's error handling was asked for */
  }
  if (!traceback && !handler) PetscCall(DriverErrorHandlerPush());
  PetscCallMPI(MPI_Comm_dup(PETSC_COMM_WORLD, &agree));
  ierr = Run(traceback, &status);
  if (ierr && (traceback || handler)) PetscCall(ierr); /* PETSc's own end of the report: the options, MPI_Abort() */
  if (ierr) {
    (void)DriverProgressClear(); /* the error message starts on a clean line */
    return DriverErrorReport(ierr, agree);
  }
  PetscCallMPI(MPI_Comm_free(&agree));
  PetscCall(PetscFinalize());
  MPI_Finalize();
  return status;
}
