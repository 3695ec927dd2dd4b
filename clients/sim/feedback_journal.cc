#include "feedback_journal.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

#include "absl/strings/escaping.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"

namespace seaplan::sim {
namespace {

absl::Status Errno(const std::string& what, const std::string& path) {
  return absl::UnavailableError(absl::StrCat(what, " ", path, ": ", std::strerror(errno)));
}

}  // namespace

absl::StatusOr<FeedbackJournal> FeedbackJournal::Open(const std::string& path) {
  FeedbackJournal j;
  j.path_ = path;
  // Replay: reports in order, minus the acknowledged ones.
  std::map<std::int64_t, size_t> index;  // sequence -> position in `order`
  std::vector<JournalEntry> order;
  std::vector<bool> acked;
  {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string text = ss.str();
    size_t start = 0;
    int line_no = 0;
    while (start < text.size()) {
      const size_t end = text.find('\n', start);
      ++line_no;
      if (end == std::string::npos) break;  // torn last line: never sent
      const std::string line = text.substr(start, end - start);
      start = end + 1;
      std::vector<std::string> f = absl::StrSplit(line, ' ');
      std::int64_t seq = 0;
      if (f.size() < 2 || !absl::SimpleAtoi(f[1], &seq)) {
        return absl::DataLossError(absl::StrCat(path, ":", line_no, ": unreadable journal record"));
      }
      if (f[0] == "R" && f.size() == 3) {
        JournalEntry e;
        e.sequence = seq;
        if (!absl::Base64Unescape(f[2], &e.payload)) {
          return absl::DataLossError(absl::StrCat(path, ":", line_no, ": bad base64"));
        }
        if (seq > j.max_sequence_) j.max_sequence_ = seq;
        if (index.count(seq) == 0) {
          index[seq] = order.size();
          order.push_back(std::move(e));
          acked.push_back(false);
        }
      } else if (f[0] == "A" && f.size() == 2) {
        if (auto it = index.find(seq); it != index.end()) acked[it->second] = true;
      } else {
        return absl::DataLossError(
            absl::StrCat(path, ":", line_no, ": unknown journal record '", line.substr(0, 2), "'"));
      }
    }
    if (start < text.size()) {
      // Cut the torn tail off so the next record starts on its own line.
      if (::truncate(path.c_str(), static_cast<off_t>(start)) != 0)
        return Errno("cannot truncate", path);
    }
  }
  for (size_t i = 0; i < order.size(); ++i) {
    if (!acked[i]) j.recovered_.push_back(std::move(order[i]));
  }
  j.fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (j.fd_ < 0) return Errno("cannot open the feedback journal", path);
  return j;
}

FeedbackJournal::FeedbackJournal(FeedbackJournal&& other) noexcept {
  *this = std::move(other);
}

FeedbackJournal& FeedbackJournal::operator=(FeedbackJournal&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    path_ = std::move(other.path_);
    fd_ = other.fd_;
    other.fd_ = -1;
    recovered_ = std::move(other.recovered_);
    max_sequence_ = other.max_sequence_;
  }
  return *this;
}

FeedbackJournal::~FeedbackJournal() {
  if (fd_ >= 0) {
    ::fdatasync(fd_);
    ::close(fd_);
  }
}

absl::Status FeedbackJournal::Write(const std::string& text, bool sync) {
  if (fd_ < 0) return absl::FailedPreconditionError("the feedback journal is closed");
  size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd_, text.data() + done, text.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      return Errno("cannot write the feedback journal", path_);
    }
    done += static_cast<size_t>(n);
  }
  if (sync && ::fdatasync(fd_) != 0) return Errno("cannot sync the feedback journal", path_);
  return absl::OkStatus();
}

absl::Status FeedbackJournal::Append(const std::vector<JournalEntry>& entries) {
  if (entries.empty()) return absl::OkStatus();
  std::string text;
  for (const JournalEntry& e : entries) {
    absl::StrAppend(&text, "R ", e.sequence, " ", absl::Base64Escape(e.payload), "\n");
    if (e.sequence > max_sequence_) max_sequence_ = e.sequence;
  }
  return Write(text, /*sync=*/true);
}

absl::Status FeedbackJournal::Acknowledge(std::int64_t sequence) {
  return Write(absl::StrCat("A ", sequence, "\n"), /*sync=*/false);
}

}  // namespace seaplan::sim
