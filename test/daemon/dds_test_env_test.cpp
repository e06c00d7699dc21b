// The DDS domain reservation the process tests rely on: a domain id held by one process is never
// handed out to another while it is held, so two test programs running side by side cannot
// answer each other's requests (with ids drawn at random, 30 ids each would overlap 99 % of the
// time).
#include "test/daemon/dds_test_env.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <set>
#include <vector>

namespace rangefit::test {
namespace dds_test_env_test {

constexpr int kEach = 30;

// kEach reservations; their lock descriptors go to *fds.
std::set<std::uint32_t> reserve_many(std::vector<int>* fds) {
  std::set<std::uint32_t> domains;
  for (int i = 0; i < kEach; ++i) {
    int fd = -1;
    domains.insert(reserve_dds_domain(&fd));
    fds->push_back(fd);
  }
  return domains;
}

void release(const std::vector<int>& fds) {
  for (int fd : fds) {
    if (fd >= 0) ::close(fd);
  }
}

TEST(TestDomains, EveryReservationIsItsOwnWhileHeld) {
  std::vector<int> fds;
  const std::set<std::uint32_t> mine = reserve_many(&fds);
  EXPECT_EQ(mine.size(), static_cast<std::size_t>(kEach)) << "a domain was handed out twice";
  EXPECT_EQ(mine.count(dds_test_domain()), 0u) << "this process's own domain handed out again";
  for (std::uint32_t d : mine) {
    EXPECT_GE(d, 1u);
    EXPECT_LE(d, kTestDomains);
  }
  release(fds);
}

TEST(TestDomains, AnotherProcessGetsNoneOfTheDomainsThisOneHolds) {
  std::vector<int> fds;
  std::set<std::uint32_t> mine = reserve_many(&fds);
  mine.insert(dds_test_domain());
  int pipe_fd[2];
  ASSERT_EQ(::pipe(pipe_fd), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {  // a second test program: reserves on its own, reports its ids
    ::close(pipe_fd[0]);
    std::vector<int> theirs_fds;
    bool written = true;
    for (std::uint32_t d : reserve_many(&theirs_fds)) {
      written = written && ::write(pipe_fd[1], &d, sizeof d) == sizeof d;
    }
    ::_exit(written ? 0 : 1);
  }
  ::close(pipe_fd[1]);
  std::set<std::uint32_t> theirs;
  for (std::uint32_t d = 0; ::read(pipe_fd[0], &d, sizeof d) == sizeof d;) theirs.insert(d);
  ::close(pipe_fd[0]);
  int status = 0;
  ::waitpid(child, &status, 0);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  EXPECT_EQ(theirs.size(), static_cast<std::size_t>(kEach));
  for (std::uint32_t d : theirs) EXPECT_EQ(mine.count(d), 0u) << "both processes hold domain " << d;
  release(fds);
}

}  // namespace dds_test_env_test
}  // namespace rangefit::test
