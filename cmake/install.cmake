# What `cmake --install` puts where (GNUInstallDirs), and so what the Debian package holds
# (cmake/package.cmake). The kernels are embedded in the executable: it needs no other file.
install(TARGETS clmarch RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(FILES ${CLMARCH_DOCGEN_DIR}/clmarch.1.gz DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)
install(FILES ${CLMARCH_DOCGEN_DIR}/clmarch.bash DESTINATION ${CMAKE_INSTALL_DATADIR}/bash-completion/completions
        RENAME clmarch)
install(FILES ${CLMARCH_DOCGEN_DIR}/_clmarch DESTINATION ${CMAKE_INSTALL_DATADIR}/zsh/vendor-completions)
install(FILES ${CLMARCH_DOCGEN_DIR}/clmarch.fish DESTINATION ${CMAKE_INSTALL_DATADIR}/fish/vendor_completions.d)
install(FILES LICENSE README.md CHANGELOG.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
# The example scenes with the instance files a scene may read beside it.
install(DIRECTORY scenes/ DESTINATION ${CMAKE_INSTALL_DATADIR}/clmarch/scenes
        FILES_MATCHING PATTERN "*.yaml" PATTERN "*.json" PATTERN "*.csv")
