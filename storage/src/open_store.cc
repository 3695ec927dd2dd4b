#include "seaplan/storage/open_store.h"

#include <filesystem>

#include "absl/strings/str_cat.h"
#include "seaplan/storage/postgres_store.h"
#include "seaplan/storage/sqlite_store.h"

namespace seaplan::storage {

bool IsPostgresUrl(const std::string& database_url) {
  return database_url.starts_with("postgresql://") || database_url.starts_with("postgres://");
}

absl::StatusOr<OpenedStore> OpenStore(const std::string& database_url,
                                      const std::string& sqlite_dir) {
  if (IsPostgresUrl(database_url)) {
    SEAPLAN_ASSIGN_OR_RETURN(std::unique_ptr<PostgresStore> store,
                             PostgresStore::Open(database_url));
    return OpenedStore{std::move(store), RedactDatabaseUrl(database_url)};
  }
  if (!database_url.empty()) {
    return absl::InvalidArgumentError(
        absl::StrCat("database '", RedactDatabaseUrl(database_url),
                     "': expected postgresql://... (or nothing for SQLite in the data folder)"));
  }
  std::error_code ec;
  std::filesystem::create_directories(sqlite_dir, ec);
  if (ec) {
    return absl::UnavailableError(
        absl::StrCat("cannot create data dir '", sqlite_dir, "': ", ec.message()));
  }
  const std::string path = (std::filesystem::path(sqlite_dir) / "seaplan.db").string();
  SEAPLAN_ASSIGN_OR_RETURN(std::unique_ptr<SqliteStore> store, SqliteStore::Open(path));
  return OpenedStore{std::move(store), path};
}

}  // namespace seaplan::storage
