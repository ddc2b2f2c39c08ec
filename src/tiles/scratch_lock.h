// meshsal: the lock that marks a temporary folder meshsal-tiles-XXXXXX as in use for the
// life of its run, and the removal of stale ones: folders whose run ended without removing
// them (a crash, SIGKILL, MPI_Abort), found by a later run in the same parent folder.
//
// A folder is stale only when its lock is verifiably free: its file `lock` exists, is the
// same file after we lock it (flock, exclusive, non-blocking: a live run holds it from
// before the file has its name until the folder is gone) and belongs to this user. Never a
// process id (ranks on other machines, pid reuse), never an age. Where the file system's
// locks cannot be trusted (NFS and other network or FUSE file systems: a lock may be local
// to one client, or refused), nothing is taken for stale: the folders are left and counted.
#pragma once
#include <cstddef>
#include <string>

namespace meshsal {

constexpr const char* kScratchPrefix = "meshsal-tiles-";

// Locks the new, empty folder `dir` for as long as the returned descriptor stays open
// (close it after remove_scratch_dir). The lock file is made as `lock.new`, locked, then
// renamed to `lock`, so that no other run ever sees it unlocked. -1 where the file system
// refuses the lock: the folder then has no lock file and no other run takes it for stale.
int lock_scratch_dir(const std::string& dir);

// Removes `dir`: everything in it but its lock file, then (when all of that went) the lock
// file and the folder, so that what a removal cut short or refused leaves is still judged by
// its lock. Never follows a link; what cannot be removed stays.
void remove_scratch_dir(const std::string& dir);

// Whether flock on the file system that holds `path` can be trusted (a local one); when
// not, `name` says which it is ("nfs", "fuse", ...).
bool scratch_locks_trusted(const std::string& path, std::string* name);

// What remove_stale_scratch_dirs found in a parent folder.
struct StaleScratch {
  size_t removed = 0;  // stale folders removed
  size_t left = 0;     // folders of other runs left, the locks not trusted
};

// Removes the stale meshsal-tiles-* folders in `parent` (see above); where the locks are
// not trusted (scratch_locks_trusted) only counts the folders of other runs.
StaleScratch remove_stale_scratch_dirs(const std::string& parent, bool locks_trusted);

// One line for a person about what remove_stale_scratch_dirs did in `parent` ("note: ..."),
// "" when there is nothing to say.
// `file_system`: scratch_locks_trusted's name for it.
std::string stale_scratch_note(const std::string& parent, const StaleScratch& found, const std::string& file_system);

}  // namespace meshsal
