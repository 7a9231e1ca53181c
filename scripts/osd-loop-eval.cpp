// OpenSubdiv 3.5 (Pixar) Loop limit-surface evaluation with adaptive refinement and a patch
// table, as a peer for subdiv's Loop evaluation tests and timings
// (scripts/osd-loop-eval-fixtures.py runs it).
//
//   build: g++ -O2 -std=c++17 scripts/osd-loop-eval.cpp -losdCPU -o /tmp/peers/osd_loop_eval
//
// usage:
//   osd_loop_eval eval  IN.obj POINTS.txt OUT.txt [--level L]
//   osd_loop_eval time  IN.obj POINTS.txt [--level L] [--repeat R]
//   osd_loop_eval limit IN.obj OUT.txt
//
// IN.obj: "v x y z" and "f a b c" (triangles only; "f a/b/c" tokens, 1-based or negative).
// Scheme Sdc::SCHEME_LOOP, VTX_BOUNDARY_EDGE_ONLY, CREASE_UNIFORM, no creases.
// POINTS.txt: one point a line, "f u v": f the 0-based control triangle (file order of the "f"
// lines), (u, v) barycentric: the parameter point is (1-u-v)*c0 + u*c1 + v*c2 with c0 c1 c2 the
// face's corners in the order its "f" line lists them (lines starting with '#' are skipped).
//
// Evaluation: TopologyRefiner::RefineAdaptive to isolation level L (default 4; adaptive options
// from PatchTableFactory::Options::GetRefineAdaptiveOptions), PatchTableFactory::Create with
// default options except SetPatchPrecision<double>() (default end caps ENDCAP_GREGORY_BASIS,
// i.e. GREGORY_TRIANGLE patches around extraordinary vertices; regular patches are
// PatchDescriptor::LOOP, quartic box splines), Far::PatchMap. Control points: the base positions
// (double), refined level by level with PrimvarRefinerReal<double>::Interpolate, then the local
// points from the patch table's double local-point stencil table. Per point:
// PatchMap::FindPatch(f, u, v) and PatchTable::EvaluateBasis<double>(handle, u, v, ...) on the
// patch's control vertices. OpenSubdiv's ptex parameterization of a Loop base triangle is the
// same as ours (corner i of the face at (0,0), (1,0), (0,1) for i = 0, 1, 2; checked by
// scripts/osd-loop-eval-fixtures.py against the limit positions), and EvaluateBasis takes the
// base-face (u, v) and returns derivatives with respect to them (it normalizes to the sub-patch
// and scales the derivative weights by 2^depth, 4^depth, with a sign flip on rotated sub-
// triangles), so no conversion is needed here.
//
// eval: OUT.txt gets a first line "# regular R irregular I" (how many points fell on
//   PatchDescriptor::LOOP patches, how many on any other type, e.g. GREGORY_TRIANGLE), then one
//   line per point: "x y z dux duy duz dvx dvy dvz duux duuy duuz duvx duvy duvz dvvx dvvy dvvz"
//   (position, d/du, d/dv, d2/du2, d2/dudv, d2/dv2 in OUR (u, v)), numbers %.17g.
// time: prints one line "build_ms=B eval_ms=E points=N": B = refiner creation + adaptive
//   refinement + patch table + patch map construction; E = the minimum over R repeats (default 1)
//   of one pass over all points evaluating position, d/du, d/dv (FindPatch + EvaluateBasis +
//   weighted sums) and the unnormalized normal du x dv, std::chrono::steady_clock. The
//   control-point computation (primvar refinement + local points) is in neither; it goes to
//   stderr as "# vertex_ms=..." with a checksum of the results.
// limit: per base vertex, PrimvarRefinerReal<double>::Limit of the unrefined mesh (the limit
//   position from Loop's limit mask): "x y z", %.17g (a check of the (u, v) convention).
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/patchTableFactory.h>
#include <opensubdiv/far/patchMap.h>
#include <opensubdiv/far/stencilTable.h>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>
using namespace OpenSubdiv;

struct V3 {
  double p[3];
  void Clear(void* = 0) { p[0] = p[1] = p[2] = 0; }
  void AddWithWeight(const V3& s, double w) { p[0] += w * s.p[0]; p[1] += w * s.p[1]; p[2] += w * s.p[2]; }
};

struct Mesh {
  std::vector<V3> pos;
  std::vector<int> idx, counts;
};

static bool readObj(const char* path, Mesh& m) {
  FILE* f = fopen(path, "r");
  if (!f) { perror(path); return false; }
  char line[8192];
  int lineNo = 0;
  while (fgets(line, sizeof line, f)) {
    lineNo++;
    if (line[0] == 'v' && (line[1] == ' ' || line[1] == '\t')) {
      V3 v; v.Clear();
      if (sscanf(line + 2, "%lf %lf %lf", &v.p[0], &v.p[1], &v.p[2]) != 3) {
        fprintf(stderr, "%s:%d: bad vertex\n", path, lineNo); fclose(f); return false;
      }
      m.pos.push_back(v);
    } else if (line[0] == 'f' && (line[1] == ' ' || line[1] == '\t')) {
      std::vector<int> poly;
      char* s = line + 2;
      while (true) {
        while (*s == ' ' || *s == '\t') s++;
        char* e; long v = strtol(s, &e, 10);
        if (e == s) break;
        poly.push_back(v < 0 ? (int)(m.pos.size() + v) : (int)v - 1);
        s = e;
        while (*s && *s != ' ' && *s != '\t' && *s != '\n' && *s != '\r') s++;  // "/vt/vn"
      }
      if (poly.size() != 3) {
        fprintf(stderr, "%s:%d: face with %zu corners (triangles only)\n", path, lineNo, poly.size());
        fclose(f); return false;
      }
      for (int c : poly)
        if (c < 0 || c >= (int)m.pos.size()) {
          fprintf(stderr, "%s:%d: vertex index out of range\n", path, lineNo); fclose(f); return false;
        }
      m.counts.push_back(3);
      m.idx.insert(m.idx.end(), poly.begin(), poly.end());
    }
  }
  fclose(f);
  if (m.counts.empty()) { fprintf(stderr, "%s: no faces\n", path); return false; }
  return true;
}

struct Pt { int f; double u, v; };

static bool readPoints(const char* path, int nFaces, std::vector<Pt>& pts) {
  FILE* f = fopen(path, "r");
  if (!f) { perror(path); return false; }
  char line[1024];
  int lineNo = 0;
  while (fgets(line, sizeof line, f)) {
    lineNo++;
    char* s = line;
    while (*s == ' ' || *s == '\t') s++;
    if (*s == '#' || *s == '\n' || *s == '\r' || *s == 0) continue;
    char* e;
    Pt p;
    p.f = (int)strtol(s, &e, 10);
    bool ok = e != s;
    s = e; p.u = strtod(s, &e); ok = ok && e != s;
    s = e; p.v = strtod(s, &e); ok = ok && e != s;
    if (!ok) { fprintf(stderr, "%s:%d: expected 'f u v'\n", path, lineNo); fclose(f); return false; }
    if (p.f < 0 || p.f >= nFaces) { fprintf(stderr, "%s:%d: face %d out of range\n", path, lineNo, p.f); fclose(f); return false; }
    if (!(p.u >= 0 && p.v >= 0 && p.u + p.v <= 1 + 1e-12)) {
      fprintf(stderr, "%s:%d: (u, v) = (%g, %g) outside the triangle\n", path, lineNo, p.u, p.v); fclose(f); return false;
    }
    pts.push_back(p);
  }
  fclose(f);
  return true;
}

static Far::TopologyRefiner* createRefiner(const Mesh& m) {
  Sdc::Options opts;
  opts.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
  opts.SetCreasingMethod(Sdc::Options::CREASE_UNIFORM);
  Far::TopologyDescriptor desc;
  desc.numVertices = (int)m.pos.size();
  desc.numFaces = (int)m.counts.size();
  desc.numVertsPerFace = m.counts.data();
  desc.vertIndicesPerFace = m.idx.data();
  return Far::TopologyRefinerFactory<Far::TopologyDescriptor>::Create(
      desc, Far::TopologyRefinerFactory<Far::TopologyDescriptor>::Options(Sdc::SCHEME_LOOP, opts));
}

struct Evaluator {
  std::unique_ptr<Far::TopologyRefiner> refiner;
  std::unique_ptr<Far::PatchTable> table;
  std::unique_ptr<Far::PatchMap> map;
  std::vector<V3> cvs;  // refined vertices of all levels, then the local points

  bool build(const Mesh& m, int level) {
    refiner.reset(createRefiner(m));
    if (!refiner) return false;
    Far::PatchTableFactory::Options po(level);
    po.SetPatchPrecision<double>();
    po.SetEndCapType(Far::PatchTableFactory::Options::ENDCAP_GREGORY_BASIS);  // the default
    refiner->RefineAdaptive(po.GetRefineAdaptiveOptions());
    table.reset(Far::PatchTableFactory::Create(*refiner, po));
    if (!table) return false;
    map.reset(new Far::PatchMap(*table));
    return true;
  }

  void controlPoints(const Mesh& m) {
    int nRef = refiner->GetNumVerticesTotal(), nLocal = table->GetNumLocalPoints();
    cvs.assign(nRef + nLocal, V3());
    for (size_t i = 0; i < m.pos.size(); i++) cvs[i] = m.pos[i];
    Far::PrimvarRefinerReal<double> pr(*refiner);
    V3* src = cvs.data();
    for (int l = 1; l < refiner->GetNumLevels(); l++) {
      V3* dst = src + refiner->GetLevel(l - 1).GetNumVertices();
      pr.Interpolate(l, src, dst);
      src = dst;
    }
    if (nLocal) table->GetLocalPointStencilTable<double>()->UpdateValues(cvs.data(), cvs.data() + nRef);
  }
};

static double ms(std::chrono::steady_clock::duration d) {
  return std::chrono::duration<double, std::milli>(d).count();
}

int main(int argc, char** argv) {
  const char* usage =
      "usage: osd_loop_eval eval  IN.obj POINTS.txt OUT.txt [--level L]\n"
      "       osd_loop_eval time  IN.obj POINTS.txt [--level L] [--repeat R]\n"
      "       osd_loop_eval limit IN.obj OUT.txt\n";
  if (argc < 4) { fputs(usage, stderr); return 2; }
  std::string mode = argv[1];
  int nPos = mode == "eval" ? 5 : mode == "time" ? 4 : mode == "limit" ? 4 : -1;
  if (nPos < 0 || argc < nPos) { fputs(usage, stderr); return 2; }
  int level = 4, repeat = 1;
  for (int i = nPos; i < argc; i++) {
    if (!strcmp(argv[i], "--level") && i + 1 < argc && mode != "limit") level = atoi(argv[++i]);
    else if (!strcmp(argv[i], "--repeat") && i + 1 < argc && mode == "time") repeat = atoi(argv[++i]);
    else { fprintf(stderr, "unknown option '%s'\n%s", argv[i], usage); return 2; }
  }
  if (level < 1 || level > 10) { fputs("--level must be in 1..10\n", stderr); return 2; }
  if (repeat < 1) repeat = 1;

  Mesh m;
  if (!readObj(argv[2], m)) return 1;

  if (mode == "limit") {
    std::unique_ptr<Far::TopologyRefiner> r(createRefiner(m));
    if (!r) return 1;
    std::vector<V3> lim(m.pos.size());
    const V3* src = m.pos.data();
    V3* dst = lim.data();
    Far::PrimvarRefinerReal<double>(*r).Limit(src, dst);
    FILE* o = fopen(argv[3], "w");
    if (!o) { perror(argv[3]); return 1; }
    for (const V3& p : lim) fprintf(o, "%.17g %.17g %.17g\n", p.p[0], p.p[1], p.p[2]);
    fclose(o);
    return 0;
  }

  std::vector<Pt> pts;
  if (!readPoints(argv[3], (int)m.counts.size(), pts)) return 1;

  Evaluator ev;
  auto t0 = std::chrono::steady_clock::now();
  if (!ev.build(m, level)) { fputs("OpenSubdiv: refiner / patch table creation failed\n", stderr); return 1; }
  auto t1 = std::chrono::steady_clock::now();
  ev.controlPoints(m);
  auto t2 = std::chrono::steady_clock::now();
  const Far::PatchTable& table = *ev.table;
  const Far::PatchMap& map = *ev.map;
  const V3* cv = ev.cvs.data();

  for (const Pt& p : pts)
    if (!map.FindPatch(p.f, p.u, p.v)) { fprintf(stderr, "no patch for face %d (a hole?)\n", p.f); return 1; }

  if (mode == "eval") {
    FILE* o = fopen(argv[4], "w");
    if (!o) { perror(argv[4]); return 1; }
    std::vector<double> out(pts.size() * 18);
    size_t regular = 0;
    double w[6][20];
    for (size_t k = 0; k < pts.size(); k++) {
      const Pt& p = pts[k];
      const Far::PatchTable::PatchHandle* h = map.FindPatch(p.f, p.u, p.v);
      if (table.GetPatchArrayDescriptor(h->arrayIndex).GetType() == Far::PatchDescriptor::LOOP) regular++;
      table.EvaluateBasis(*h, p.u, p.v, w[0], w[1], w[2], w[3], w[4], w[5]);
      Far::ConstIndexArray idx = table.GetPatchVertices(*h);
      double* r = &out[k * 18];
      for (int j = 0; j < 18; j++) r[j] = 0;
      for (int i = 0; i < idx.size(); i++) {
        const double* c = cv[idx[i]].p;
        for (int d = 0; d < 6; d++)
          for (int a = 0; a < 3; a++) r[d * 3 + a] += w[d][i] * c[a];
      }
    }
    fprintf(o, "# regular %zu irregular %zu\n", regular, pts.size() - regular);
    for (size_t k = 0; k < pts.size(); k++) {
      const double* r = &out[k * 18];
      for (int j = 0; j < 18; j++) fprintf(o, j ? " %.17g" : "%.17g", r[j]);
      fputc('\n', o);
    }
    fclose(o);
    return 0;
  }

  // time
  std::vector<double> res(pts.size() * 12);
  double best = 1e300;
  for (int rep = 0; rep < repeat; rep++) {
    auto e0 = std::chrono::steady_clock::now();
    double wP[20], wDu[20], wDv[20];
    for (size_t k = 0; k < pts.size(); k++) {
      const Pt& p = pts[k];
      const Far::PatchTable::PatchHandle* h = map.FindPatch(p.f, p.u, p.v);
      table.EvaluateBasis(*h, p.u, p.v, wP, wDu, wDv);
      Far::ConstIndexArray idx = table.GetPatchVertices(*h);
      double P[3] = {0, 0, 0}, U[3] = {0, 0, 0}, V[3] = {0, 0, 0};
      for (int i = 0; i < idx.size(); i++) {
        const double* c = cv[idx[i]].p;
        for (int a = 0; a < 3; a++) { P[a] += wP[i] * c[a]; U[a] += wDu[i] * c[a]; V[a] += wDv[i] * c[a]; }
      }
      double* r = &res[k * 12];
      for (int a = 0; a < 3; a++) { r[a] = P[a]; r[3 + a] = U[a]; r[6 + a] = V[a]; }
      r[9] = U[1] * V[2] - U[2] * V[1];
      r[10] = U[2] * V[0] - U[0] * V[2];
      r[11] = U[0] * V[1] - U[1] * V[0];
    }
    auto e1 = std::chrono::steady_clock::now();
    if (ms(e1 - e0) < best) best = ms(e1 - e0);
  }
  double sum = 0;
  for (double x : res) sum += x;
  fprintf(stderr, "# vertex_ms=%.3f (primvar refinement + local points, not in build_ms) refined=%d local=%d patches=%d checksum=%.17g\n",
          ms(t2 - t1), ev.refiner->GetNumVerticesTotal(), table.GetNumLocalPoints(), table.GetNumPatchesTotal(), sum);
  printf("build_ms=%.3f eval_ms=%.3f points=%zu\n", ms(t1 - t0), best, pts.size());
  return 0;
}
