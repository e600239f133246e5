// MeshLab 2020.09 filter plugin: "Intrinsic Symmetry: Detect", and "Intrinsic Symmetry: Detect
// with Repeated Parts" (the same with the library's partial symmetries between repeated parts,
// sym_params_set_parts). A thin layer over the intrinsym C API (include/intrinsym.h): packs the
// current mesh, calls sym_detect with MeshLab's progress bar as the callback, and writes
// per-vertex quality and colour.
#ifndef FILTER_INTRINSYM_H
#define FILTER_INTRINSYM_H

#include <common/interfaces.h>

#include "intrinsym.h"

class FilterIntrinsymPlugin : public QObject, public MeshFilterInterface
{
    Q_OBJECT
    MESHLAB_PLUGIN_IID_EXPORTER(MESH_FILTER_INTERFACE_IID)
    Q_INTERFACES(MeshFilterInterface)

public:
    // The parts variant is a filter of its own, not a parameter: MeshLab 2020.09's meshlabserver
    // aborts on a saved script that does not list every parameter of its filter (README).
    enum { FP_INTRINSIC_SYMMETRY, FP_INTRINSIC_SYMMETRY_PARTS };

    FilterIntrinsymPlugin();
    ~FilterIntrinsymPlugin();

    QString pluginName() const;
    QString filterName(FilterIDType filter) const;
    QString filterInfo(FilterIDType filter) const;
    FilterClass getClass(QAction *a);
    FILTER_ARITY filterArity(QAction *) const;
    int getPreConditions(QAction *) const;
    int postCondition(QAction *) const;
    void initParameterSet(QAction *, MeshModel &m, RichParameterList &parlst);
    bool applyFilter(QAction *action, MeshDocument &md, const RichParameterList &par, vcg::CallBackPos *cb);

private:
    // The last detection and the fingerprint of what it was computed from (the packed mesh
    // and the detection parameters): a re-run with only the colouring or the shown symmetry
    // changed (MeshLab's Preview re-applies the filter on every change) reuses it.
    sym_result *cached = nullptr;
    unsigned long long cachedKey = 0;
};

#endif
