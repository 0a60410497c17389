// SPDX-License-Identifier: MIT
// The tessera command line tool.
int main() { return 0; }
