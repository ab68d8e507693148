// rpvio-bench's task manifest (apps/lib/bench_tasks.h) and Slurm array ranges: what every executor
// runs from, without a cluster.
#include <gtest/gtest.h>

#include "apps/lib/bench_tasks.h"
#include "apps/lib/slurm_executor.h"
#include "common/input_error.h"
#include "tests/test_util.h"

namespace rpvio::apps {
namespace {

TEST(BenchTasks, ManifestReadsBackAndATaskLeavesItsStatus) {
  test::TempDir dir;
  const std::vector<BenchTask> tasks = {
      {"fails",
       dir.file("a"),
       dir.file("a/log.txt"),
       dir.file("a/task.json"),
       {"/bin/sh", "-c", "echo 'to the log'; exit 3"}},
      {"succeeds", "", dir.file("b.log"), dir.file("status/b.json"), {"true"}}};
  writeManifest(dir.file("tasks.tsv"), tasks);
  const auto back = readManifest(dir.file("tasks.tsv"));
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[0].argv, tasks[0].argv);
  EXPECT_EQ(back[1].status, tasks[1].status);
  EXPECT_FALSE(readTaskStatus(back[0]));
  EXPECT_EQ(runTask(back[0]), 3);
  EXPECT_EQ(readTaskStatus(back[0])->exit_code, 3);
  EXPECT_EQ(test::readFile(dir.file("a/log.txt")), "to the log\n");
  EXPECT_EQ(runTask(back[1]), 0);  // found in PATH
  EXPECT_EQ(readTaskStatus(back[1])->exit_code, 0);
}

TEST(BenchTasks, MalformedManifestNamesTheLine) {
  test::TempDir dir;
  test::writeText(dir.file("tasks.tsv"), "a\tb\tc\td\ttrue\nonly\ttwo\n");
  try {
    readManifest(dir.file("tasks.tsv"));
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("tasks.tsv:line 2:"), std::string::npos) << e.what();
  }
  EXPECT_THROW(writeManifest(dir.file("x.tsv"), {{"tab\tin name", "", "l", "s", {"true"}}}),
               InputError);
}

TEST(SlurmExecutor, ArrayRangesCompressRuns) {
  EXPECT_EQ(arrayRanges({0, 1, 2, 3, 7, 9, 10}), "0-3,7,9-10");
  EXPECT_EQ(arrayRanges({5}), "5");
  EXPECT_EQ(arrayRanges({}), "");
}

}  // namespace
}  // namespace rpvio::apps
