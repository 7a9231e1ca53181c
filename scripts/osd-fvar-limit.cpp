// OpenSubdiv 3.5 (Pixar) face-varying interpolation and limit evaluation, as a peer for subdiv's
// Catmull-Clark tests (scripts/osd-fvar-limit-fixtures.py runs it).
//
//   build: g++ -O2 -std=c++17 scripts/osd-fvar-limit.cpp -losdCPU -o /tmp/peers/osd_fvar_limit
//
// usage:
//   osd_fvar_limit uv    IN.obj LEVEL all|corners OUT.txt [--corners] [--chaikin]
//   osd_fvar_limit limit IN.obj LEVEL OUT.txt [--corners] [--chaikin] [--e0]
//
// Both read "v x y z", "f a b c ..." (polygons of any size; "f v/vt/vn" tokens, 1-based or negative)
// and OpenSubdiv's OBJ tags "t crease 2/1/0 a b s" and "t corner 1/1/0 v s" (0-based vertex ids,
// s >= 10 infinitely sharp). Scheme Sdc::SCHEME_CATMARK with its default triangle rule
// (TRI_SUB_CATMARK); --corners = VTX_BOUNDARY_EDGE_AND_CORNER (default VTX_BOUNDARY_EDGE_ONLY),
// --chaikin = CREASE_CHAIKIN (default CREASE_UNIFORM). Uniform refinement to LEVEL with
// fullTopologyInLastLevel; positions are interpolated level by level with
// PrimvarRefiner::Interpolate. Numbers are written with %.9g.
//
// uv: also reads "vt u v" and the vt index of each face corner (every corner must have one) as one
//   face-varying channel, with FVAR_LINEAR_ALL ("all") or FVAR_LINEAR_CORNERS_ONLY ("corners"),
//   interpolated with PrimvarRefiner::InterpolateFaceVarying. OUT.txt:
//     # faces F                    (faces at LEVEL)
//     c x y z u v                  (for each face at LEVEL, in OpenSubdiv's order, for each of its
//                                   corners in order: the corner's vertex position and its UV)
// limit: positions only; after refinement, PrimvarRefiner::Limit(src, pos, tan1, tan2) on the
//   vertices of LEVEL. OUT.txt:
//     # vertices N                 (vertices at LEVEL)
//     l px py pz lx ly lz tx ty tz sx sy sz [ex ey ez]
//   per vertex at LEVEL in OpenSubdiv's order: refined position, limit position, the two limit
//   tangents as returned (tan1, tan2; not normalized); with --e0 also the refined position of the
//   other end of the vertex's first incident edge (GetVertexEdges(v)[0]), which fixes the frame in
//   which OpenSubdiv's tangent masks are laid out (edges and faces counter-clockwise from edge 0).
//   stdout gets one line "semi-sharp at level L: E edges, V vertices" (features OpenSubdiv's
//   Limit treats as infinitely sharp: its vertex rules count semi-sharp edges as sharp).
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/primvarRefiner.h>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>
using namespace OpenSubdiv;

struct V3 {
  float p[3];
  void Clear(void* = 0) { p[0] = p[1] = p[2] = 0; }
  void AddWithWeight(const V3& s, float w) { p[0] += w * s.p[0]; p[1] += w * s.p[1]; p[2] += w * s.p[2]; }
};
struct V2 {
  float p[2];
  void Clear(void* = 0) { p[0] = p[1] = 0; }
  void AddWithWeight(const V2& s, float w) { p[0] += w * s.p[0]; p[1] += w * s.p[1]; }
};

struct Mesh {
  std::vector<V3> pos;
  std::vector<V2> uv;
  std::vector<int> idx, uvIdx, counts;
  std::vector<int> creasePairs, cornerIds;
  std::vector<float> creaseW, cornerW;
  bool allCornersHaveUV = true;
};

static bool readObj(const char* path, Mesh& m) {
  FILE* f = fopen(path, "r");
  if (!f) { perror(path); return false; }
  char line[8192];
  while (fgets(line, sizeof line, f)) {
    if (line[0] == 'v' && line[1] == ' ') {
      V3 v; sscanf(line + 2, "%f %f %f", &v.p[0], &v.p[1], &v.p[2]); m.pos.push_back(v);
    } else if (line[0] == 'v' && line[1] == 't' && line[2] == ' ') {
      V2 t; t.p[0] = t.p[1] = 0; sscanf(line + 3, "%f %f", &t.p[0], &t.p[1]); m.uv.push_back(t);
    } else if (!strncmp(line, "t crease 2/1", 12)) {
      int a, b; float w; const char* q = line + 12; if (!strncmp(q, "/0", 2)) q += 2;
      if (sscanf(q, "%d %d %f", &a, &b, &w) == 3) { m.creasePairs.push_back(a); m.creasePairs.push_back(b); m.creaseW.push_back(w); }
    } else if (!strncmp(line, "t corner 1/1", 12)) {
      int a; float w; const char* q = line + 12; if (!strncmp(q, "/0", 2)) q += 2;
      if (sscanf(q, "%d %f", &a, &w) == 2) { m.cornerIds.push_back(a); m.cornerW.push_back(w); }
    } else if (line[0] == 'f' && line[1] == ' ') {
      std::vector<int> poly, tex;
      char* s = line + 2;
      while (true) {
        while (*s == ' ' || *s == '\t') s++;
        char* e; long v = strtol(s, &e, 10);
        if (e == s) break;
        poly.push_back(v < 0 ? (int)(m.pos.size() + v) : (int)v - 1);
        s = e;
        int t = -1;
        if (*s == '/') {
          s++;
          long vt = strtol(s, &e, 10);
          if (e != s) { t = vt < 0 ? (int)(m.uv.size() + vt) : (int)vt - 1; s = e; }
        }
        if (t < 0) m.allCornersHaveUV = false;
        tex.push_back(t);
        while (*s && *s != ' ' && *s != '\t' && *s != '\n' && *s != '\r') s++;
      }
      if (poly.size() >= 3) {
        m.counts.push_back((int)poly.size());
        m.idx.insert(m.idx.end(), poly.begin(), poly.end());
        m.uvIdx.insert(m.uvIdx.end(), tex.begin(), tex.end());
      }
    }
  }
  fclose(f);
  return true;
}

int main(int argc, char** argv) {
  const char* usage =
      "usage: osd_fvar_limit uv IN.obj LEVEL all|corners OUT.txt [--corners] [--chaikin]\n"
      "       osd_fvar_limit limit IN.obj LEVEL OUT.txt [--corners] [--chaikin] [--e0]\n";
  if (argc < 5) { fputs(usage, stderr); return 2; }
  std::string mode = argv[1];
  bool uvMode = mode == "uv";
  if (!uvMode && mode != "limit") { fputs(usage, stderr); return 2; }
  if (uvMode && argc < 6) { fputs(usage, stderr); return 2; }
  const char* in = argv[2];
  int level = atoi(argv[3]);
  std::string fvarMode = uvMode ? argv[4] : "";
  if (uvMode && fvarMode != "all" && fvarMode != "corners") { fputs(usage, stderr); return 2; }
  const char* out = uvMode ? argv[5] : argv[4];
  bool corners = false, chaikin = false, e0 = false;
  for (int i = uvMode ? 6 : 5; i < argc; i++) {
    if (!strcmp(argv[i], "--corners")) corners = true;
    else if (!strcmp(argv[i], "--chaikin")) chaikin = true;
    else if (!strcmp(argv[i], "--e0") && !uvMode) e0 = true;
    else { fprintf(stderr, "unknown option '%s'\n%s", argv[i], usage); return 2; }
  }
  if (level < 0) { fputs("LEVEL must be >= 0\n", stderr); return 2; }

  Mesh m;
  if (!readObj(in, m)) return 1;
  if (uvMode && (m.uv.empty() || !m.allCornersHaveUV)) { fprintf(stderr, "%s: uv mode needs a vt index on every face corner\n", in); return 1; }

  Sdc::Options opts;
  opts.SetVtxBoundaryInterpolation(corners ? Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER : Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
  opts.SetCreasingMethod(chaikin ? Sdc::Options::CREASE_CHAIKIN : Sdc::Options::CREASE_UNIFORM);
  if (uvMode)
    opts.SetFVarLinearInterpolation(fvarMode == "all" ? Sdc::Options::FVAR_LINEAR_ALL : Sdc::Options::FVAR_LINEAR_CORNERS_ONLY);

  typedef Far::TopologyDescriptor Desc;
  Desc desc;
  desc.numVertices = (int)m.pos.size();
  desc.numFaces = (int)m.counts.size();
  desc.numVertsPerFace = m.counts.data();
  desc.vertIndicesPerFace = m.idx.data();
  desc.numCreases = (int)m.creaseW.size();
  desc.creaseVertexIndexPairs = m.creasePairs.data();
  desc.creaseWeights = m.creaseW.data();
  desc.numCorners = (int)m.cornerW.size();
  desc.cornerVertexIndices = m.cornerIds.data();
  desc.cornerWeights = m.cornerW.data();
  Desc::FVarChannel channel;
  if (uvMode) {
    channel.numValues = (int)m.uv.size();
    channel.valueIndices = m.uvIdx.data();
    desc.numFVarChannels = 1;
    desc.fvarChannels = &channel;
  }
  Far::TopologyRefiner* r = Far::TopologyRefinerFactory<Desc>::Create(
      desc, Far::TopologyRefinerFactory<Desc>::Options(Sdc::SCHEME_CATMARK, opts));
  if (!r) { fputs("topology refiner failed\n", stderr); return 1; }
  if (level > 0) {
    Far::TopologyRefiner::UniformOptions uo(level);
    uo.fullTopologyInLastLevel = true;
    r->RefineUniform(uo);
  }

  std::vector<V3> verts(r->GetNumVerticesTotal());
  for (size_t i = 0; i < m.pos.size(); i++) verts[i] = m.pos[i];
  Far::PrimvarRefiner pr(*r);
  V3* src = verts.data();
  for (int l = 1; l <= level; l++) {
    V3* dst = src + r->GetLevel(l - 1).GetNumVertices();
    pr.Interpolate(l, src, dst);
    src = dst;
  }
  const Far::TopologyLevel& last = r->GetLevel(level);

  FILE* o = fopen(out, "w");
  if (!o) { perror(out); return 1; }
  if (uvMode) {
    std::vector<V2> uvs(r->GetNumFVarValuesTotal(0));
    for (size_t i = 0; i < m.uv.size(); i++) uvs[i] = m.uv[i];
    V2* usrc = uvs.data();
    for (int l = 1; l <= level; l++) {
      V2* udst = usrc + r->GetLevel(l - 1).GetNumFVarValues(0);
      pr.InterpolateFaceVarying(l, usrc, udst, 0);
      usrc = udst;
    }
    fprintf(o, "# faces %d\n", last.GetNumFaces());
    for (int fi = 0; fi < last.GetNumFaces(); fi++) {
      Far::ConstIndexArray fv = last.GetFaceVertices(fi);
      Far::ConstIndexArray fu = last.GetFaceFVarValues(fi, 0);
      for (int k = 0; k < fv.size(); k++) {
        const V3& p = src[fv[k]];
        const V2& t = usrc[fu[k]];
        fprintf(o, "c %.9g %.9g %.9g %.9g %.9g\n", p.p[0], p.p[1], p.p[2], t.p[0], t.p[1]);
      }
    }
    printf("osd uv %s level %d: %d faces, %d fvar values\n", fvarMode.c_str(), level, last.GetNumFaces(), last.GetNumFVarValues(0));
  } else {
    int nv = last.GetNumVertices();
    std::vector<V3> lp(nv), t1(nv), t2(nv);
    pr.Limit(src, lp, t1, t2);
    int semiEdges = 0, semiVerts = 0;
    for (int e = 0; e < last.GetNumEdges(); e++) {
      float s = last.GetEdgeSharpness(e);
      if (Sdc::Crease::IsSemiSharp(s)) semiEdges++;
    }
    for (int v = 0; v < nv; v++)
      if (Sdc::Crease::IsSemiSharp(last.GetVertexSharpness(v))) semiVerts++;
    fprintf(o, "# vertices %d\n", nv);
    for (int v = 0; v < nv; v++) {
      const float *p = src[v].p, *q = lp[v].p, *a = t1[v].p, *b = t2[v].p;
      fprintf(o, "l %.9g %.9g %.9g %.9g %.9g %.9g %.9g %.9g %.9g %.9g %.9g %.9g", p[0], p[1], p[2], q[0], q[1], q[2],
              a[0], a[1], a[2], b[0], b[1], b[2]);
      if (e0) {
        Far::ConstIndexArray ve = last.GetVertexEdges(v);
        if (ve.size() > 0) {
          Far::ConstIndexArray ev = last.GetEdgeVertices(ve[0]);
          const float* n = src[ev[0] == v ? ev[1] : ev[0]].p;
          fprintf(o, " %.9g %.9g %.9g", n[0], n[1], n[2]);
        } else {
          fprintf(o, " %.9g %.9g %.9g", p[0], p[1], p[2]);
        }
      }
      fputc('\n', o);
    }
    printf("semi-sharp at level %d: %d edges, %d vertices\n", level, semiEdges, semiVerts);
  }
  fclose(o);
  delete r;
  return 0;
}
