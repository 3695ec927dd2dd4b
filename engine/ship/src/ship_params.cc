#include "seaplan/ship/ship_params.h"

#include <cmath>
#include <string>

#include "absl/strings/str_cat.h"

namespace seaplan::ship {
namespace {

Status RequirePositive(const char* name, double value) {
  if (!std::isfinite(value) || value <= 0.0) {
    return absl::InvalidArgumentError(
        absl::StrCat("ShipParams.", name, " must be finite and > 0, got ", value));
  }
  return absl::OkStatus();
}
Status RequireNonNegative(const char* where, const char* name, double value) {
  if (!std::isfinite(value) || value < 0.0) {
    return absl::InvalidArgumentError(
        absl::StrCat(where, ".", name, " must be finite and >= 0, got ", value));
  }
  return absl::OkStatus();
}

}  // namespace

double ShipParams::Mass() const {
  if (mass_override_kg > 0.0) return mass_override_kg;
  const double payload = payload_fraction * (dead_weight_tonnage_kg - bunkers_kg);
  const double lightship =
      dead_weight_tonnage_kg / dwt_to_displacement_coefficient - dead_weight_tonnage_kg;
  return lightship + payload + bunkers_kg + ballast_kg;
}

double ShipParams::YawInertia() const {
  if (yaw_inertia_override_kgm2 > 0.0) return yaw_inertia_override_kgm2;
  return Mass() * (length_m * length_m + beam_m * beam_m) / 12.0;
}

Status ShipParams::Validate() const {
  if (mass_override_kg <= 0.0) {
    SEAPLAN_RETURN_IF_ERROR(RequirePositive("dead_weight_tonnage_kg", dead_weight_tonnage_kg));
    SEAPLAN_RETURN_IF_ERROR(
        RequirePositive("dwt_to_displacement_coefficient", dwt_to_displacement_coefficient));
    SEAPLAN_RETURN_IF_ERROR(RequireNonNegative("ShipParams", "bunkers_kg", bunkers_kg));
    SEAPLAN_RETURN_IF_ERROR(RequireNonNegative("ShipParams", "ballast_kg", ballast_kg));
    SEAPLAN_RETURN_IF_ERROR(RequireNonNegative("ShipParams", "payload_fraction", payload_fraction));
  } else {
    SEAPLAN_RETURN_IF_ERROR(RequirePositive("mass_override_kg", mass_override_kg));
  }
  SEAPLAN_RETURN_IF_ERROR(RequirePositive("length_m", length_m));
  SEAPLAN_RETURN_IF_ERROR(RequirePositive("beam_m", beam_m));
  if (!std::isfinite(x_g_m)) return absl::InvalidArgumentError("ShipParams.x_g_m must be finite");
  SEAPLAN_RETURN_IF_ERROR(RequireNonNegative("ShipParams", "added_mass_coefficient_surge",
                                             added_mass_coefficient_surge));
  SEAPLAN_RETURN_IF_ERROR(
      RequireNonNegative("ShipParams", "added_mass_coefficient_sway", added_mass_coefficient_sway));
  SEAPLAN_RETURN_IF_ERROR(
      RequireNonNegative("ShipParams", "added_mass_coefficient_yaw", added_mass_coefficient_yaw));
  SEAPLAN_RETURN_IF_ERROR(
      RequirePositive("damping_time_constant_surge_s", damping_time_constant_surge_s));
  SEAPLAN_RETURN_IF_ERROR(
      RequirePositive("damping_time_constant_sway_s", damping_time_constant_sway_s));
  SEAPLAN_RETURN_IF_ERROR(
      RequirePositive("damping_time_constant_yaw_s", damping_time_constant_yaw_s));
  SEAPLAN_RETURN_IF_ERROR(
      RequireNonNegative("ShipParams", "nonlinear_damping_surge", nonlinear_damping_surge));
  SEAPLAN_RETURN_IF_ERROR(
      RequireNonNegative("ShipParams", "nonlinear_damping_sway", nonlinear_damping_sway));
  SEAPLAN_RETURN_IF_ERROR(
      RequireNonNegative("ShipParams", "nonlinear_damping_yaw", nonlinear_damping_yaw));
  SEAPLAN_RETURN_IF_ERROR(RequireNonNegative("ShipParams", "air_density_kgpm3", air_density_kgpm3));
  SEAPLAN_RETURN_IF_ERROR(RequireNonNegative("ShipParams", "front_height_m", front_height_m));
  SEAPLAN_RETURN_IF_ERROR(RequireNonNegative("ShipParams", "side_height_m", side_height_m));
  for (double c : {wind_coefficient_x, wind_coefficient_y, wind_coefficient_n,
                   rudder_sway_coefficient, rudder_yaw_coefficient}) {
    if (!std::isfinite(c)) {
      return absl::InvalidArgumentError("ShipParams: wind/rudder coefficients must be finite");
    }
  }
  SEAPLAN_RETURN_IF_ERROR(RequirePositive("max_rudder_angle_rad", max_rudder_angle_rad));
  if (Mass() <= 0.0) {
    return absl::InvalidArgumentError(absl::StrCat("ShipParams: derived mass ", Mass(), " <= 0"));
  }
  return absl::OkStatus();
}

Status Environment::Validate() const {
  SEAPLAN_RETURN_IF_ERROR(RequireNonNegative("Environment", "wind_speed_mps", wind_speed_mps));
  if (!std::isfinite(wind_direction_from_rad) || !std::isfinite(current_north_mps) ||
      !std::isfinite(current_east_mps)) {
    return absl::InvalidArgumentError(
        "Environment: wind direction and current components must be finite");
  }
  return absl::OkStatus();
}

}  // namespace seaplan::ship
