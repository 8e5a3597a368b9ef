// What the fuzz targets share: the bytes libFuzzer made, written to a file for the reader
// under test (every reader takes a path), and the rule for what counts as a finding.
//
// A reader may refuse its input only with hdrf::Error (a message naming the file): any
// other exception (std::bad_alloc, std::out_of_range, a JSON library's type error) reaches
// the user as "unexpected error" and is a finding, so it is left to escape to libFuzzer,
// which reports it with the input; so are crashes, leaks and undefined behaviour (the
// targets are built with AddressSanitizer and UBSan).
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>

namespace hdrf::fuzz {

// Writes the bytes to `name` in this process's scratch folder (in /dev/shm where it
// exists) and returns its path; the same path each call, overwritten.
std::filesystem::path AsFile(const std::uint8_t* data, std::size_t size, const char* name);

// Runs `read`, swallowing hdrf::Error only.
void Expect(const std::function<void()>& read);

}  // namespace hdrf::fuzz
