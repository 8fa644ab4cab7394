#pragma once
// Outputs appear whole or not at all, and a crash leaves either the old file or the new one:
// each is written to a temporary of its own beside the destination (created with O_EXCL, named
// by process and call, so two processes or threads never share one), fsynced, renamed over the
// destination (atomic on POSIX), and the folder fsynced so that the rename itself is durable.
// A failure removes the temporary and throws subdfit::Error naming the destination.
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace subdfit::io {

// Why `destination` may not be written ("" when it may): an output replaces nothing but a
// regular file (never a folder, a FIFO, a device such as /dev/null, a socket or a symlink).
std::string outputFileProblem(const std::filesystem::path& destination);

// Throws subdfit::Error naming `destination` when it is empty, its name is longer than a file
// name may be, it is `input` (the same file by any name), or outputFileProblem finds one: a
// command checks its outputs before it works.
void checkOutputFile(const std::filesystem::path& destination, const std::filesystem::path& input = {});

// For writers that stream bytes themselves. Refuses (outputFileProblem) when created and again
// just before the rename.
class AtomicFile {
public:
    explicit AtomicFile(std::filesystem::path destination);
    ~AtomicFile();  // removes the temporary unless committed
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    void write(std::string_view bytes);
    // Durably replaces the destination with what was written.
    void commit();

private:
    friend void writeAtomically(const std::filesystem::path&, const std::function<void(const std::filesystem::path&)>&);
    [[noreturn]] void fail(const std::string& what) const;

    std::filesystem::path destination_, temporary_;
    int fd_ = -1;
};

// For writers that want a path to write to (OpenImageIO, the glTF and Draco writers): `write`
// fills the temporary it is given, whose extension is the destination's (writers pick formats
// by extension).
void writeAtomically(const std::filesystem::path& destination,
                     const std::function<void(const std::filesystem::path& temporary)>& write);

void writeTextAtomically(const std::filesystem::path& destination, std::string_view text);

// Several outputs that belong together (a chain of levels of detail and its JSON): every one is
// written to its temporary before the first is renamed, so that a failure while writing (a name
// too long, a full disk) leaves none of them.
void writeFilesTogether(const std::vector<std::pair<std::filesystem::path, std::string_view>>& files);

}  // namespace subdfit::io
