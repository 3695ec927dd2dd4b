// Opens the store a server is configured with: one setting chooses the
// backend.
//
//   database_url empty                      SQLite, <sqlite_dir>/seaplan.db
//                                           (the folder is created if missing)
//   postgresql://... or postgres://...      PostgreSQL (libpq connection URI)
//
// Anything else is InvalidArgument, so a typo never silently falls back to a
// local file.
#pragma once

#include <memory>
#include <string>

#include "seaplan/storage/repositories.h"

namespace seaplan::storage {

struct OpenedStore {
  std::unique_ptr<Store> store;
  // Where the data lives, for the start-up log line (no password).
  std::string description;
};

absl::StatusOr<OpenedStore> OpenStore(const std::string& database_url,
                                      const std::string& sqlite_dir);

// True when `database_url` names a PostgreSQL database.
bool IsPostgresUrl(const std::string& database_url);

}  // namespace seaplan::storage
