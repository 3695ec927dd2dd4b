#include "seaplan/chart/geodesy.h"

#include <array>
#include <cmath>
#include <numbers>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"

namespace seaplan::chart {
namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;
constexpr double kRadToDeg = 180.0 / std::numbers::pi;

// WGS84 ellipsoid. ETRS89 uses GRS80, whose flattening differs in the 11th
// significant digit: below 0.1 mm in UTM coordinates, so one set serves both.
constexpr double kA = 6378137.0;
constexpr double kF = 1.0 / 298.257223563;
constexpr double kK0 = 0.9996;
constexpr double kFalseEasting = 500000.0;
constexpr double kFalseNorthingSouth = 10000000.0;

// Coefficients of Karney (2011), "Transverse Mercator with an accuracy of a
// few nanometers", eq. 35 and 36, to order n^6.
struct KruegerSeries {
  double e;       // first eccentricity
  double a_rect;  // rectifying radius A
  std::array<double, 6> alpha;
  std::array<double, 6> beta;
};

KruegerSeries MakeSeries() {
  KruegerSeries s{};
  const double n = kF / (2.0 - kF);
  const double n2 = n * n, n3 = n2 * n, n4 = n3 * n, n5 = n4 * n, n6 = n5 * n;
  s.e = std::sqrt(kF * (2.0 - kF));
  s.a_rect = kA / (1.0 + n) * (1.0 + n2 / 4.0 + n4 / 64.0 + n6 / 256.0);
  s.alpha = {n / 2 - 2 * n2 / 3 + 5 * n3 / 16 + 41 * n4 / 180 - 127 * n5 / 288 + 7891 * n6 / 37800,
             13 * n2 / 48 - 3 * n3 / 5 + 557 * n4 / 1440 + 281 * n5 / 630 - 1983433 * n6 / 1935360,
             61 * n3 / 240 - 103 * n4 / 140 + 15061 * n5 / 26880 + 167603 * n6 / 181440,
             49561 * n4 / 161280 - 179 * n5 / 168 + 6601661 * n6 / 7257600,
             34729 * n5 / 80640 - 3418889 * n6 / 1995840,
             212378941 * n6 / 319334400};
  s.beta = {n / 2 - 2 * n2 / 3 + 37 * n3 / 96 - n4 / 360 - 81 * n5 / 512 + 96199 * n6 / 604800,
            n2 / 48 + n3 / 15 - 437 * n4 / 1440 + 46 * n5 / 105 - 1118711 * n6 / 3870720,
            17 * n3 / 480 - 37 * n4 / 840 - 209 * n5 / 4480 + 5569 * n6 / 90720,
            4397 * n4 / 161280 - 11 * n5 / 504 - 830251 * n6 / 7257600,
            4583 * n5 / 161280 - 108847 * n6 / 3991680,
            20648693 * n6 / 638668800};
  return s;
}

const KruegerSeries& Series() {
  static const KruegerSeries kSeries = MakeSeries();
  return kSeries;
}

}  // namespace

std::string FormatLatLon(LatLon p) {
  return absl::StrFormat("%.5f,%.5f", p.lat_deg, p.lon_deg);
}

double HaversineDistanceM(LatLon a, LatLon b) {
  const double lat1 = a.lat_deg * kDegToRad, lat2 = b.lat_deg * kDegToRad;
  const double dlat = lat2 - lat1;
  const double dlon = (b.lon_deg - a.lon_deg) * kDegToRad;
  const double s = std::sin(dlat / 2), t = std::sin(dlon / 2);
  const double h = s * s + std::cos(lat1) * std::cos(lat2) * t * t;
  return 2.0 * kEarthRadiusM * std::asin(std::min(1.0, std::sqrt(h)));
}

double InitialBearingDeg(LatLon a, LatLon b) {
  const double lat1 = a.lat_deg * kDegToRad, lat2 = b.lat_deg * kDegToRad;
  const double dlon = (b.lon_deg - a.lon_deg) * kDegToRad;
  const double y = std::sin(dlon) * std::cos(lat2);
  const double x =
      std::cos(lat1) * std::sin(lat2) - std::sin(lat1) * std::cos(lat2) * std::cos(dlon);
  double deg = std::atan2(y, x) * kRadToDeg;
  if (deg < 0) deg += 360.0;
  return deg >= 360.0 ? 0.0 : deg;
}

LocalFrame LocalFrame::ForCentre(LatLon centre) {
  double lon = std::fmod(centre.lon_deg + 180.0, 360.0);
  if (lon < 0) lon += 360.0;
  int zone = static_cast<int>(std::floor(lon / 6.0)) + 1;
  if (zone > 60) zone = 60;
  const bool north = centre.lat_deg >= 0.0;
  return LocalFrame((north ? 32600 : 32700) + zone, zone, north);
}

StatusOr<LocalFrame> LocalFrame::FromEpsg(int epsg) {
  if (epsg > 32600 && epsg <= 32660) return LocalFrame(epsg, epsg - 32600, true);
  if (epsg > 32700 && epsg <= 32760) return LocalFrame(epsg, epsg - 32700, false);
  if (epsg >= 25828 && epsg <= 25838) return LocalFrame(epsg, epsg - 25800, true);
  return absl::InvalidArgumentError(
      absl::StrCat("frame EPSG:", epsg, " is not a UTM frame (use 326zz, 327zz or 25828..25838)"));
}

double LocalFrame::central_meridian_deg() const {
  return -183.0 + 6.0 * zone_;
}

EastNorth LocalFrame::ToLocal(LatLon p) const {
  const KruegerSeries& s = Series();
  const double phi = p.lat_deg * kDegToRad;
  double dlon = p.lon_deg - central_meridian_deg();
  dlon = std::remainder(dlon, 360.0);
  const double lam = dlon * kDegToRad;
  const double sin_phi = std::sin(phi);
  const double t = std::sinh(std::atanh(sin_phi) - s.e * std::atanh(s.e * sin_phi));
  const double xi_p = std::atan2(t, std::cos(lam));
  const double eta_p = std::atanh(std::sin(lam) / std::sqrt(1.0 + t * t));
  double xi = xi_p, eta = eta_p;
  for (int j = 1; j <= 6; ++j) {
    const double a = s.alpha[j - 1];
    xi += a * std::sin(2 * j * xi_p) * std::cosh(2 * j * eta_p);
    eta += a * std::cos(2 * j * xi_p) * std::sinh(2 * j * eta_p);
  }
  return {kFalseEasting + kK0 * s.a_rect * eta,
          (north_ ? 0.0 : kFalseNorthingSouth) + kK0 * s.a_rect * xi};
}

LatLon LocalFrame::ToLatLon(EastNorth p) const {
  const KruegerSeries& s = Series();
  const double xi = (p.north_m - (north_ ? 0.0 : kFalseNorthingSouth)) / (kK0 * s.a_rect);
  const double eta = (p.east_m - kFalseEasting) / (kK0 * s.a_rect);
  double xi_p = xi, eta_p = eta;
  for (int j = 1; j <= 6; ++j) {
    const double b = s.beta[j - 1];
    xi_p -= b * std::sin(2 * j * xi) * std::cosh(2 * j * eta);
    eta_p -= b * std::cos(2 * j * xi) * std::sinh(2 * j * eta);
  }
  const double sinh_eta = std::sinh(eta_p), cos_xi = std::cos(xi_p);
  const double tau_p = std::sin(xi_p) / std::sqrt(sinh_eta * sinh_eta + cos_xi * cos_xi);
  const double lam = std::atan2(sinh_eta, cos_xi);
  // Newton on tau (Karney eq. 19-21); converges in 2-3 steps.
  const double e2 = s.e * s.e;
  double tau = tau_p;
  for (int i = 0; i < 8; ++i) {
    const double sq = std::sqrt(1.0 + tau * tau);
    const double sigma = std::sinh(s.e * std::atanh(s.e * tau / sq));
    const double tau_i = tau * std::sqrt(1.0 + sigma * sigma) - sigma * sq;
    const double dtau = (tau_p - tau_i) / std::sqrt(1.0 + tau_i * tau_i) *
                        (1.0 + (1.0 - e2) * tau * tau) / ((1.0 - e2) * sq);
    tau += dtau;
    if (std::abs(dtau) < 1e-14) break;
  }
  return {std::atan(tau) * kRadToDeg, central_meridian_deg() + lam * kRadToDeg};
}

}  // namespace seaplan::chart
