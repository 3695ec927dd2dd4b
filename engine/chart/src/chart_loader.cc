// Reading charts with GDAL/OGR and selecting grounding obstacles (see the
// rules in obstacle_map.h).
#include <algorithm>
#include <atomic>
#include <cctype>
#include <charconv>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "absl/strings/ascii.h"
#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "absl/strings/str_split.h"
#include "cpl_conv.h"
#include "cpl_error.h"
#include "cpl_string.h"
#include "cpl_vsi.h"
#include "gdal_priv.h"
#include "obstacle_map_internal.h"
#include "ogr_geometry.h"
#include "ogr_spatialref.h"
#include "ogrsf_frmts.h"
#include "seaplan/chart/obstacle_map.h"
#include "seaplan/common/log.h"

namespace seaplan::chart {
namespace {

using internal::GeomPtr;
using internal::GeosContext;
using internal::Own;

void InitGdal() {
  static std::once_flag once;
  std::call_once(once, [] {
    GDALAllRegister();
    // The S-57 driver needs no S57 attribute files for what we read; keep
    // GDAL quiet on the console (our error handler captures messages).
    CPLSetConfigOption("CPL_LOG", "/dev/null");
  });
}

// Captures GDAL/CPL messages of the current thread while alive (GDAL's error
// handler stack is per thread), so nothing reaches stderr and errors can be
// quoted in statuses.
class ErrorCapture {
 public:
  ErrorCapture() { CPLPushErrorHandlerEx(&ErrorCapture::Handler, this); }
  ~ErrorCapture() { CPLPopErrorHandler(); }
  ErrorCapture(const ErrorCapture&) = delete;
  ErrorCapture& operator=(const ErrorCapture&) = delete;

  std::string Joined() const { return absl::StrJoin(messages_, "; "); }
  void Clear() { messages_.clear(); }

 private:
  static void CPL_STDCALL Handler(CPLErr cls, CPLErrorNum, const char* msg) {
    auto* self = static_cast<ErrorCapture*>(CPLGetErrorHandlerUserData());
    if (self == nullptr || cls == CE_Debug || cls == CE_None) return;
    if (self->messages_.size() < 8) self->messages_.emplace_back(msg != nullptr ? msg : "?");
  }
  std::vector<std::string> messages_;
};

std::string Lower(std::string_view s) {
  return absl::AsciiStrToLower(std::string(s));
}

std::string Extension(std::string_view path) {
  const size_t slash = path.find_last_of('/');
  const size_t dot = path.find_last_of('.');
  if (dot == std::string_view::npos || (slash != std::string_view::npos && dot < slash)) return "";
  return Lower(path.substr(dot + 1));
}

std::string BaseName(std::string_view path) {
  while (!path.empty() && path.back() == '/') path.remove_suffix(1);
  const size_t slash = path.find_last_of('/');
  return std::string(slash == std::string_view::npos ? path : path.substr(slash + 1));
}

bool IsDir(const std::string& path) {
  VSIStatBufL st;
  return VSIStatL(path.c_str(), &st) == 0 && VSI_ISDIR(st.st_mode);
}
bool Exists(const std::string& path) {
  VSIStatBufL st;
  return VSIStatL(path.c_str(), &st) == 0;
}

// Finds the datasets (S-57 cells, .gdb folders, shapefiles, GeoJSON) under a
// folder or archive. Returns them sorted for deterministic results.
absl::Status Discover(const std::string& root, const std::string& display, int depth,
                      std::vector<std::string>* out, bool archive_root = false) {
  if (depth > 3) return absl::OkStatus();
  if (!archive_root && !IsDir(root)) {
    const std::string ext = Extension(root);
    if (ext == "zip") {
      // The root of an archive does not stat as a folder; listing it is the
      // readability test (an empty list is NULL too: also "unreadable").
      const std::string inner = absl::StrCat("/vsizip/", root);
      char** entries = VSIReadDir(inner.c_str());
      if (entries == nullptr) {
        return absl::InvalidArgumentError(
            absl::StrCat("'", display, "' is not a readable (or is an empty) zip archive"));
      }
      CSLDestroy(entries);
      return Discover(inner, display, depth + 1, out, true);
    }
    out->push_back(root);
    return absl::OkStatus();
  }
  if (Extension(root) == "gdb") {
    out->push_back(root);
    return absl::OkStatus();
  }
  char** entries = VSIReadDirRecursive(root.c_str());
  std::vector<std::string> names;
  for (int i = 0; entries != nullptr && entries[i] != nullptr; ++i) names.emplace_back(entries[i]);
  CSLDestroy(entries);
  std::sort(names.begin(), names.end());
  std::vector<std::string> gdbs;
  for (std::string name : names) {
    while (!name.empty() && name.back() == '/') name.pop_back();
    // A .gdb folder is one dataset: skip its inner files.
    const size_t gdb = Lower(name).find(".gdb");
    if (gdb != std::string::npos) {
      const std::string dir = name.substr(0, gdb + 4);
      if (std::find(gdbs.begin(), gdbs.end(), dir) == gdbs.end()) gdbs.push_back(dir);
      continue;
    }
    const std::string ext = Extension(name);
    const std::string full = absl::StrCat(root, "/", name);
    if (ext == "000" || ext == "shp" || ext == "geojson" || ext == "json") {
      out->push_back(full);
    } else if (ext == "zip") {
      SEAPLAN_RETURN_IF_ERROR(Discover(full, absl::StrCat(display, "/", name), depth + 1, out));
    }
  }
  for (const std::string& g : gdbs) out->push_back(absl::StrCat(root, "/", g));
  return absl::OkStatus();
}

// How a source layer contributes.
enum class Role { kSkip, kAll, kDepthArea, kHazard, kSeabed, kCoverage, kGeneric };

struct LayerRule {
  Role role = Role::kSkip;
  std::string depth_field;    // for kDepthArea / kHazard
  double seabed_depth_m = 0;  // for kSeabed
};

LayerRule Classify(const std::string& driver, const std::string& layer, OGRFeatureDefn* defn) {
  const std::string l = Lower(layer);
  if (driver == "S57") {
    if (layer == "LNDARE") return {Role::kAll};
    if (layer == "DEPARE" || layer == "DRGARE") return {Role::kDepthArea, "DRVAL1"};
    if (layer == "UNSARE") return {Role::kAll};
    if (layer == "OBSTRN" || layer == "WRECKS" || layer == "UWTROC")
      return {Role::kHazard, "VALSOU"};
    if (layer == "M_COVR") return {Role::kCoverage};
    return {Role::kSkip};
  }
  // Kartverket "Sjokart - Dybdedata" product layers (FileGDB, or exports of
  // them that keep the layer names, e.g. GeoJSON with its "name" member).
  if (l == "landareal" || l == "torrfall" || l == "skjer" || l == "ikkekartlagtsjomaltomr") {
    return {Role::kAll};
  }
  if (l == "dybdeareal") return {Role::kDepthArea, "minimumsdybde"};
  if (l == "grunne") return {Role::kHazard, "dybde"};
  if (driver == "OpenFileGDB") return {Role::kSkip};
  // seacharts' processed product (the Alesund set): seabed<N>m = sea at
  // least N m deep.
  if (absl::StartsWith(l, "seabed")) {
    double n = 0;
    const std::string digits =
        l.substr(6, l.find('m', 6) == std::string::npos ? std::string::npos : l.find('m', 6) - 6);
    const auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), n);
    if (ec == std::errc() && ptr == digits.data() + digits.size() && l == "seabed" + digits + "m") {
      LayerRule r{Role::kSeabed};
      r.seabed_depth_m = n;
      return r;
    }
    return {Role::kSkip};
  }
  // Anything else by its schema: a depth attribute (S-57 DRVAL1 / VALSOU,
  // Kartverket minimumsdybde / dybde) makes the features shallower than the
  // minimum depth obstacles; without one, every feature is (plain land or
  // obstacle polygons, coastlines, hazard points).
  for (const char* field : {"DRVAL1", "minimumsdybde", "VALSOU", "dybde"}) {
    if (defn != nullptr && defn->GetFieldIndex(field) >= 0) return {Role::kDepthArea, field};
  }
  return {Role::kGeneric};
}

struct SourceGeometry {
  std::unique_ptr<OGRGeometry> geometry;  // in the source SRS until projected
  std::shared_ptr<OGRSpatialReference> srs;
  std::string layer;
  Role role = Role::kAll;
  double seabed_depth_m = 0;
};

struct Extent {
  double min_x = std::numeric_limits<double>::infinity();
  double min_y = std::numeric_limits<double>::infinity();
  double max_x = -std::numeric_limits<double>::infinity();
  double max_y = -std::numeric_limits<double>::infinity();
  bool empty() const { return !(min_x <= max_x); }
  void Include(double x, double y) {
    min_x = std::min(min_x, x);
    min_y = std::min(min_y, y);
    max_x = std::max(max_x, x);
    max_y = std::max(max_y, y);
  }
};

struct ExtentInSrs {
  Extent extent;
  std::shared_ptr<OGRSpatialReference> srs;
};

std::shared_ptr<OGRSpatialReference> SrsOf(OGRLayer* layer) {
  auto srs = std::make_shared<OGRSpatialReference>();
  const OGRSpatialReference* s = layer->GetSpatialRef();
  if (s != nullptr) {
    *srs = *s;
  } else {
    srs->SetWellKnownGeogCS("WGS84");
  }
  srs->SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  return srs;
}

// Densified outline of an extent, transformed to `target`; returns the
// transformed envelope (empty on failure).
Extent TransformExtent(const ExtentInSrs& e, const OGRSpatialReference& target) {
  Extent out;
  std::unique_ptr<OGRCoordinateTransformation> ct(
      OGRCreateCoordinateTransformation(e.srs.get(), &target));
  if (!ct) return out;
  constexpr int kSteps = 8;
  for (int i = 0; i <= kSteps; ++i) {
    for (int j = 0; j <= kSteps; ++j) {
      if (i != 0 && i != kSteps && j != 0 && j != kSteps) continue;
      double x = e.extent.min_x + (e.extent.max_x - e.extent.min_x) * i / kSteps;
      double y = e.extent.min_y + (e.extent.max_y - e.extent.min_y) * j / kSteps;
      if (!ct->Transform(1, &x, &y)) continue;
      out.Include(x, y);
    }
  }
  return out;
}

// Union of the sources' envelopes in `target`; a source that does not
// transform (empty envelope) is left out rather than widening the union.
Extent TransformedUnion(const std::vector<ExtentInSrs>& sources,
                        const OGRSpatialReference& target) {
  Extent out;
  for (const ExtentInSrs& e : sources) {
    const Extent t = TransformExtent(e, target);
    if (t.empty()) continue;
    out.Include(t.min_x, t.min_y);
    out.Include(t.max_x, t.max_y);
  }
  return out;
}

struct GdalDatasetCloser {
  void operator()(GDALDataset* d) const { GDALClose(d); }
};

GeomPtr ToGeos(const GeosContext& c, OGRGeometry* g) {
  g->flattenTo2D();
  const size_t size = g->WkbSize();
  std::string wkb(size, '\0');
  if (g->exportToWkb(wkbNDR, reinterpret_cast<unsigned char*>(wkb.data()), wkbVariantIso) !=
      OGRERR_NONE) {
    return Own(c, nullptr);
  }
  GEOSWKBReader* reader = GEOSWKBReader_create_r(c.get());
  GEOSGeometry* out = GEOSWKBReader_read_r(
      c.get(), reader, reinterpret_cast<const unsigned char*>(wkb.data()), wkb.size());
  GEOSWKBReader_destroy_r(c.get(), reader);
  return Own(c, out);
}

bool IsAreal(OGRwkbGeometryType t) {
  const OGRwkbGeometryType f = wkbFlatten(t);
  return f == wkbPolygon || f == wkbMultiPolygon || f == wkbCurvePolygon || f == wkbMultiSurface;
}

StatusOr<ObstacleMap> LoadFromRoot(const std::string& root, const std::string& display,
                                   const ChartOptions& options) {
  SEAPLAN_RETURN_IF_ERROR(options.Validate());
  InitGdal();
  ErrorCapture errors;
  if (!Exists(root))
    return absl::NotFoundError(absl::StrCat("chart '", display, "' does not exist"));
  std::vector<std::string> datasets;
  SEAPLAN_RETURN_IF_ERROR(Discover(root, display, 0, &datasets));
  if (datasets.empty()) {
    return absl::InvalidArgumentError(absl::StrCat(
        "no chart found in '", display, "' (looked for S-57 .000, FileGDB .gdb, .shp, .geojson)"));
  }

  const auto t_start = std::chrono::steady_clock::now();
  auto ms_since = [](std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
  };
  ObstacleSummary summary;
  summary.options = options;
  std::vector<SourceGeometry> sources;
  std::vector<ExtentInSrs> extents;  // all recognised layers: chart box
  std::vector<ExtentInSrs> m_covr;   // S-57 coverage when present
  std::vector<std::string> drivers;
  int recognised_layers = 0;
  int skipped_features = 0;
  int opened = 0;
  std::vector<std::string> unreadable;
  std::vector<std::string> layer_names;

  for (const std::string& path : datasets) {
    errors.Clear();
    const bool s57 = Extension(path) == "000";
    static const char* const kS57Options[] = {"UPDATES=APPLY",
                                              "SPLIT_MULTIPOINT=ON",
                                              "ADD_SOUNDG_DEPTH=ON",
                                              "RETURN_PRIMITIVES=OFF",
                                              "RETURN_LINKAGES=OFF",
                                              "LNAM_REFS=OFF",
                                              nullptr};
    // Only the chart formats: an upload must not reach GDAL's other
    // drivers (OSM, SQLite-based, network ones...), whose cost and attack
    // surface have nothing to do with charts (a 36-byte "<osm" upload took
    // the OSM driver over 10 s under the fuzzer).
    static const char* const kChartDrivers[] = {"S57", "OpenFileGDB", "ESRI Shapefile", "GeoJSON",
                                                nullptr};
    std::unique_ptr<GDALDataset, GdalDatasetCloser> ds(
        GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, kChartDrivers,
                          s57 ? kS57Options : nullptr, nullptr));
    if (!ds) {
      // In a folder or archive with several datasets, one unreadable file
      // (a stray metadata .json) is a warning; the load fails only if no
      // dataset can be read at all.
      const std::string why = errors.Joined();
      unreadable.push_back(absl::StrCat("'", BaseName(path), "' is not a chart GDAL can read",
                                        why.empty() ? "" : absl::StrCat(" (", why, ")")));
      continue;
    }
    ++opened;
    const std::string driver = ds->GetDriver() != nullptr ? ds->GetDriver()->GetDescription() : "?";
    if (std::find(drivers.begin(), drivers.end(), driver) == drivers.end())
      drivers.push_back(driver);
    for (OGRLayer* layer : ds->GetLayers()) {
      std::string name = layer->GetName();
      // Shapefile sets: the layer name is the file stem ("seabed5m").
      layer_names.push_back(name);
      const LayerRule rule = Classify(driver, name, layer->GetLayerDefn());
      if (rule.role == Role::kSkip) continue;
      ++recognised_layers;
      auto srs = SrsOf(layer);
      OGREnvelope env;
      if (layer->GetExtent(&env, TRUE) == OGRERR_NONE) {
        ExtentInSrs e{{env.MinX, env.MinY, env.MaxX, env.MaxY}, srs};
        (rule.role == Role::kCoverage ? m_covr : extents).push_back(e);
      }
      if (rule.role == Role::kCoverage) continue;
      const int field = rule.depth_field.empty()
                            ? -1
                            : layer->GetLayerDefn()->GetFieldIndex(rule.depth_field.c_str());
      layer->ResetReading();
      int taken = 0;
      for (auto& feature : *layer) {
        OGRGeometry* g = feature->GetGeometryRef();
        if (g == nullptr || g->IsEmpty()) continue;
        const OGRwkbGeometryType type = wkbFlatten(g->getGeometryType());
        if (rule.role == Role::kDepthArea || rule.role == Role::kHazard ||
            rule.role == Role::kGeneric) {
          if (rule.role == Role::kDepthArea && !IsAreal(type) && driver == "S57") continue;
          bool obstacle = true;
          if (field >= 0 && feature->IsFieldSetAndNotNull(field)) {
            obstacle = feature->GetFieldAsDouble(field) < options.min_depth_m;
          } else if (field >= 0 || rule.role == Role::kHazard) {
            obstacle = options.unknown_depth_is_obstacle;
          }
          if (!obstacle) continue;
        }
        if (type == wkbGeometryCollection || type == wkbUnknown || type == wkbNone) {
          ++skipped_features;
          continue;
        }
        SourceGeometry s;
        s.geometry.reset(g->clone());
        s.srs = srs;
        s.layer = name;
        s.role = rule.role;
        s.seabed_depth_m = rule.seabed_depth_m;
        sources.push_back(std::move(s));
        ++taken;
      }
      if (rule.role != Role::kSeabed) summary.features_per_layer[name] += taken;
    }
  }
  if (opened == 0) {
    return absl::InvalidArgumentError(absl::StrCat("'", display, "': ", unreadable.front()));
  }
  for (const std::string& u : unreadable) summary.warnings.push_back(absl::StrCat(u, "; skipped"));
  summary.source_format = absl::StrJoin(drivers, "+");
  if (recognised_layers == 0) {
    return absl::InvalidArgumentError(absl::StrCat(
        "'", display, "' has no obstacle layer (layers: ", absl::StrJoin(layer_names, ", "),
        "); expected S-57 LNDARE/DEPARE, Kartverket landareal/"
        "dybdeareal, seabed<N>m or plain polygons"));
  }
  const std::vector<ExtentInSrs>& box_sources = m_covr.empty() ? extents : m_covr;
  // Chart centre in WGS84 -> frame.
  OGRSpatialReference wgs84;
  wgs84.SetWellKnownGeogCS("WGS84");
  wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  const Extent geo = TransformedUnion(box_sources, wgs84);
  if (geo.empty()) {
    return absl::InvalidArgumentError(
        absl::StrCat("'", display, "' contains no features (empty chart)"));
  }
  if (geo.min_y < -90.0 || geo.max_y > 90.0 || geo.min_x < -180.0 || geo.max_x > 180.0) {
    return absl::InvalidArgumentError(absl::StrCat(
        "'", display, "': chart extent is not a valid position (lon ", geo.min_x, "..", geo.max_x,
        ", lat ", geo.min_y, "..", geo.max_y, "); wrong or missing coordinate system?"));
  }
  LocalFrame frame =
      LocalFrame::ForCentre({(geo.min_y + geo.max_y) / 2, (geo.min_x + geo.max_x) / 2});
  if (options.frame_epsg != 0) {
    SEAPLAN_ASSIGN_OR_RETURN(frame, LocalFrame::FromEpsg(options.frame_epsg));
  }
  OGRSpatialReference target;
  if (target.importFromEPSG(frame.epsg()) != OGRERR_NONE) {
    return absl::InternalError(
        absl::StrCat("PROJ does not know EPSG:", frame.epsg(), " (", errors.Joined(), ")"));
  }
  target.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  const Extent box = TransformedUnion(box_sources, target);
  summary.coverage = {{box.min_x, box.min_y}, {box.max_x, box.max_y}};

  const double read_ms = ms_since(t_start);
  const auto t_project = std::chrono::steady_clock::now();
  // Project and convert to GEOS.
  GeosContext c;
  std::vector<GeomPtr> areas;
  std::vector<int> tiled_group;  // per area: tiled layer group or -1
  std::map<std::string, int> group_of_layer;
  std::map<double, std::vector<GeomPtr>> seabeds;
  std::map<const OGRSpatialReference*, std::unique_ptr<OGRCoordinateTransformation>> transforms;
  int failed = 0;
  for (SourceGeometry& s : sources) {
    auto& ct = transforms[s.srs.get()];
    if (!ct) ct.reset(OGRCreateCoordinateTransformation(s.srs.get(), &target));
    if (!ct || s.geometry->transform(ct.get()) != OGRERR_NONE) {
      ++failed;
      continue;
    }
    const OGRwkbGeometryType type = wkbFlatten(s.geometry->getGeometryType());
    if (wkbFlatten(type) == wkbCurvePolygon || type == wkbMultiSurface ||
        type == wkbCompoundCurve || type == wkbCircularString || type == wkbMultiCurve) {
      s.geometry.reset(s.geometry->getLinearGeometry());
    }
    GeomPtr g = ToGeos(c, s.geometry.get());
    if (!g) {
      ++failed;
      continue;
    }
    const int gt = GEOSGeomTypeId_r(c.get(), g.get());
    const bool areal = gt == GEOS_POLYGON || gt == GEOS_MULTIPOLYGON;
    if (s.role == Role::kSeabed) {
      if (areal) seabeds[s.seabed_depth_m].push_back(std::move(g));
      continue;
    }
    int group = -1;
    if (areal && (s.role == Role::kAll || s.role == Role::kDepthArea)) {
      // S-57 group-1 objects tile the cell together; other formats per layer.
      // Other sources: layers overlap each other (torrfall over landareal)
      // and their coverage union is slow on dense coastlines: thin + overlay.
      const bool s57 = summary.source_format == "S57";
      const std::string key = s57 ? "S57" : s.layer;
      group = group_of_layer
                  .emplace(key, static_cast<int>(group_of_layer.size()) +
                                    (s57 ? 0 : internal::kPreSimplifyGroup))
                  .first->second;
    }
    if (!areal) {
      // Point and line hazards become discs / corridors of the hazard radius.
      g = Own(c, GEOSBuffer_r(c.get(), g.get(), options.point_hazard_radius_m, 8));
      if (!g) {
        ++failed;
        continue;
      }
    }
    areas.push_back(std::move(g));
    tiled_group.push_back(group);
  }
  sources.clear();
  if (failed > 0) {
    summary.warnings.push_back(
        absl::StrCat(failed, " feature(s) could not be projected or converted; skipped"));
  }
  if (skipped_features > 0) {
    summary.warnings.push_back(
        absl::StrCat(skipped_features, " feature(s) with unsupported geometry type skipped"));
  }
  if (!seabeds.empty()) {
    // seabed<N>m is the sea at least N m deep, so only a layer with N >= D is
    // all deep enough (smaller N would count N..D m water as navigable).
    // Take the smallest such N: it gives up the least navigable water. With
    // no such layer the chart cannot tell where the water is D m deep;
    // falling back to the deepest layer would let the ship into shallower
    // water, and treating the whole chart as an obstacle would hide the cause,
    // so the load fails and names the deepest layer the set has.
    auto it = seabeds.lower_bound(options.min_depth_m);
    if (it == seabeds.end()) {
      return absl::InvalidArgumentError(
          absl::StrCat("'", display, "': no seabed<N>m layer with N >= min depth ",
                       options.min_depth_m, " m: the deepest is seabed", seabeds.rbegin()->first,
                       "m, which includes water shallower than the minimum depth"));
    }
    const double n = it->first;
    GeomPtr sea = internal::MakeCollection(c, GEOS_GEOMETRYCOLLECTION, std::move(it->second));
    sea = Own(c, GEOSUnaryUnion_r(c.get(), sea.get()));
    bool repaired = false;
    sea = internal::MakeValidPolygonal(c, std::move(sea), &repaired);
    GeomPtr chart_box = internal::MakeBox(c, summary.coverage);
    GeomPtr shallow = sea ? Own(c, GEOSDifference_r(c.get(), chart_box.get(), sea.get())) : nullptr;
    if (!shallow) {
      return absl::InvalidArgumentError(absl::StrCat("'", display, "': cannot subtract seabed", n,
                                                     "m from the chart box: ", c.TakeError()));
    }
    std::vector<GeomPtr> parts = internal::PolygonParts(c, shallow.get());
    summary.features_per_layer[absl::StrCat("chart_box-minus-seabed", n, "m")] =
        static_cast<int>(parts.size());
    for (GeomPtr& p : parts) {
      areas.push_back(std::move(p));
      tiled_group.push_back(-1);
    }
  }
  const double project_ms = ms_since(t_project);
  const auto t_build = std::chrono::steady_clock::now();
  const size_t area_count = areas.size();
  auto map = internal::BuildObstacleMap(c, std::move(areas), std::move(tiled_group), frame, options,
                                        std::move(summary));
  log::Info(
      "chart '{}': {} obstacle areas from {} ({} dataset(s)), frame EPSG:{}; read {:.0f} ms, "
      "project {:.0f} ms, "
      "buffer+union {:.0f} ms",
      display, area_count, drivers.empty() ? "?" : drivers[0], datasets.size(), frame.epsg(),
      read_ms, project_ms, ms_since(t_build));
  return map;
}

}  // namespace

StatusOr<ObstacleMap> LoadChartFile(const std::string& path, const ChartOptions& options) {
  if (path.empty()) return absl::InvalidArgumentError("chart path is empty");
  std::string root = path;
  while (root.size() > 1 && root.back() == '/') root.pop_back();
  return LoadFromRoot(root, path, options);
}

StatusOr<ObstacleMap> LoadChartBytes(const std::vector<ChartFile>& files,
                                     const ChartOptions& options) {
  if (files.empty()) return absl::InvalidArgumentError("no chart file given");
  SEAPLAN_RETURN_IF_ERROR(options.Validate());
  InitGdal();
  static std::atomic<uint64_t> counter{0};
  const std::string dir = absl::StrCat("/vsimem/seaplan_chart_", ++counter);
  VSIMkdir(dir.c_str(), 0755);
  std::vector<std::string> written;
  std::vector<std::string> tops;  // top-level names, for messages
  std::string display;
  std::vector<std::string> folders;  // created below `dir`, deepest last
  auto clean_up = [&] {
    for (const std::string& w : written) VSIUnlink(w.c_str());
    for (auto it = folders.rbegin(); it != folders.rend(); ++it) VSIRmdir(it->c_str());
    VSIRmdir(dir.c_str());
  };
  for (const ChartFile& f : files) {
    // A name is a file name or a relative path inside an uploaded folder
    // ("Trondheim.gdb/a00000009.gdbtable", "alesund/land/land.shp").
    std::vector<std::string> parts = absl::StrSplit(f.name, '/');
    const bool plain = !parts.empty() && std::all_of(parts.begin(), parts.end(), [](const auto& p) {
      return !p.empty() && p != "." && p != "..";
    });
    if (!plain) {
      clean_up();
      return absl::InvalidArgumentError(absl::StrCat(
          "chart file name '", f.name, "' is not a file name or a relative path in a folder"));
    }
    std::string path = dir;
    for (size_t i = 0; i + 1 < parts.size(); ++i) {
      path = absl::StrCat(path, "/", parts[i]);
      if (std::find(folders.begin(), folders.end(), path) == folders.end()) {
        VSIMkdir(path.c_str(), 0755);
        folders.push_back(path);
      }
    }
    path = absl::StrCat(path, "/", parts.back());
    // No copy: the bytes outlive the load (GDAL only reads them).
    VSILFILE* fp = VSIFileFromMemBuffer(path.c_str(),
                                        reinterpret_cast<GByte*>(const_cast<char*>(f.bytes.data())),
                                        static_cast<vsi_l_offset>(f.bytes.size()), FALSE);
    if (fp != nullptr) VSIFCloseL(fp);
    written.push_back(path);
    if (std::find(tops.begin(), tops.end(), parts.front()) == tops.end()) {
      tops.push_back(parts.front());
      display = display.empty() ? parts.front() : absl::StrCat(display, "+", parts.front());
    }
  }
  auto result = LoadFromRoot(written.size() == 1 ? written[0] : dir, display, options);
  clean_up();
  return result;
}

}  // namespace seaplan::chart
