#include "seaplan/chart/geodesy.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "ogr_spatialref.h"

namespace seaplan::chart {
namespace {

TEST(Haversine, QuarterMeridianAndZero) {
  // Equator to pole along a meridian: pi/2 * R.
  EXPECT_NEAR(HaversineDistanceM({0, 10}, {90, 10}), M_PI / 2 * kEarthRadiusM, 1e-6);
  EXPECT_DOUBLE_EQ(HaversineDistanceM({63.4, 10.4}, {63.4, 10.4}), 0.0);
  // One degree of longitude on the equator.
  EXPECT_NEAR(HaversineDistanceM({0, 0}, {0, 1}), kEarthRadiusM * M_PI / 180, 1e-6);
}

TEST(Bearing, CardinalDirections) {
  EXPECT_NEAR(InitialBearingDeg({0, 0}, {1, 0}), 0.0, 1e-9);
  EXPECT_NEAR(InitialBearingDeg({0, 0}, {0, 1}), 90.0, 1e-9);
  EXPECT_NEAR(InitialBearingDeg({0, 0}, {-1, 0}), 180.0, 1e-9);
  EXPECT_NEAR(InitialBearingDeg({0, 0}, {0, -1}), 270.0, 1e-9);
}

TEST(LocalFrame, ZoneByCentreAndEpsg) {
  EXPECT_EQ(LocalFrame::ForCentre({63.43, 10.39}).epsg(), 32632);  // Trondheim
  EXPECT_EQ(LocalFrame::ForCentre({38.7, -76.3}).epsg(), 32618);   // Chesapeake Bay
  EXPECT_EQ(LocalFrame::ForCentre({-33.9, 151.2}).epsg(), 32756);  // Sydney
  EXPECT_EQ(LocalFrame::FromEpsg(25833)->zone(), 33);
  EXPECT_FALSE(LocalFrame::FromEpsg(4326).ok());
  EXPECT_FALSE(LocalFrame::FromEpsg(32661).ok());
}

TEST(LocalFrame, CentralMeridianPointIsFalseEasting) {
  const LocalFrame f = *LocalFrame::FromEpsg(32633);
  const EastNorth p = f.ToLocal({0.0, 15.0});
  EXPECT_NEAR(p.east_m, 500000.0, 1e-6);
  EXPECT_NEAR(p.north_m, 0.0, 1e-6);
}

TEST(LocalFrame, RoundTripBelowOneMillimetre) {
  for (const LatLon ll : {LatLon{63.43, 10.39}, LatLon{62.48, 6.0}, LatLon{38.7, -76.3},
                          LatLon{-33.9, 151.2}, LatLon{0.001, 2.999}, LatLon{79.0, 20.0}}) {
    const LocalFrame f = LocalFrame::ForCentre(ll);
    for (double dlat : {-0.2, 0.0, 0.3}) {
      for (double dlon : {-2.5, 0.0, 2.9}) {
        const LatLon q{ll.lat_deg + dlat, ll.lon_deg + dlon};
        const LatLon back = f.ToLatLon(f.ToLocal(q));
        EXPECT_LT(HaversineDistanceM(q, back), 1e-3) << q.lat_deg << " " << q.lon_deg;
      }
    }
  }
}

// Our Krueger series against PROJ (through OGR): the loader projects chart
// data with PROJ and callers convert with the series, so they must agree.
TEST(LocalFrame, AgreesWithProjBelowOneMillimetre) {
  for (int epsg : {32632, 32633, 32618, 32756, 25833}) {
    OGRSpatialReference wgs84, utm;
    wgs84.SetWellKnownGeogCS("WGS84");
    wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    ASSERT_EQ(utm.importFromEPSG(epsg), OGRERR_NONE);
    utm.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    std::unique_ptr<OGRCoordinateTransformation> ct(
        OGRCreateCoordinateTransformation(&wgs84, &utm));
    ASSERT_NE(ct, nullptr);
    const LocalFrame f = *LocalFrame::FromEpsg(epsg);
    const double cm = f.central_meridian_deg();
    const double lat0 = f.north() ? 50.0 : -30.0;
    for (double dlat : {-8.0, 0.0, 13.0}) {
      for (double dlon : {-2.9, -1.0, 0.0, 2.0, 2.9}) {
        double x = cm + dlon, y = lat0 + dlat;
        if (epsg == 25833) {
          // ETRS89 vs WGS84 datum shift: PROJ may apply a (ballpark) null
          // transform; compare only the projection maths.
        }
        ASSERT_TRUE(ct->Transform(1, &x, &y));
        const EastNorth p = f.ToLocal({lat0 + dlat, cm + dlon});
        EXPECT_NEAR(p.east_m, x, 1e-3) << epsg << " " << dlat << " " << dlon;
        EXPECT_NEAR(p.north_m, y, 1e-3) << epsg << " " << dlat << " " << dlon;
      }
    }
  }
}

}  // namespace
}  // namespace seaplan::chart
