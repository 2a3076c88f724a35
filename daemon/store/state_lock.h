#pragma once
// One daemon per state database (docs/operations.md "State database"): two
// daemons on one file would each write their own ledger and settings over
// the other's, the last write winning. The daemon takes an exclusive
// flock(2) on "<database>.lock" before it opens the database and holds it
// until it exits; the kernel drops it when the process dies, even by kill -9,
// so a crash never leaves a stale lock behind. The lock file holds the
// holder's pid, for the message the second daemon prints.
//
// The lock follows the file, not the name it was given: the lock file sits
// beside the path with every symlink resolved, so a --state-db that is a
// symlink to (or through a symlinked directory to) a running daemon's
// database finds that daemon's lock (docs/operations.md). A hard link is a
// second name the kernel does not tell apart; it is not followed.
#include <string>

namespace xr {

class StateLock {
 public:
  enum class Result {
    Held,         // ours until destruction
    HeldByOther,  // another process has it: do not start
    NoLockFile,   // the lock file cannot be made (read-only directory): nothing will be written either
  };
  explicit StateLock(const std::string& databasePath);
  ~StateLock();
  StateLock(const StateLock&) = delete;
  StateLock& operator=(const StateLock&) = delete;

  Result result() const { return result_; }
  // For the log: who holds it, or why there is none.
  const std::string& message() const { return message_; }
  const std::string& path() const { return path_; }
  // The database's path with every symlink resolved (the path itself when
  // it cannot be resolved).
  static std::string resolvedPath(const std::string& databasePath);

 private:
  std::string path_;
  int fd_ = -1;
  Result result_ = Result::NoLockFile;
  std::string message_;
};

}  // namespace xr
